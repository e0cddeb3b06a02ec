#include "core/math/float_util.h"

#include <gtest/gtest.h>

#include <limits>

namespace penumbra {
namespace {

TEST(FloatUtil, RadianceIsValidOnlyWhenFiniteAndNonNegativeInEveryChannel) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  EXPECT_TRUE(isValidRadiance(Color3(0.f)));
  EXPECT_TRUE(isValidRadiance(Color3(1e30f, 0.f, 2.f)));
  EXPECT_TRUE(isValidRadiance(Color3(-0.f, 0.f, 0.f)));  // negative zero adds nothing
  for (int c = 0; c < 3; ++c)
    for (float bad : {nan, inf, -inf, -1e-30f}) {
      Color3 L(1.f);
      L[c] = bad;
      EXPECT_FALSE(isValidRadiance(L)) << "channel " << c << " = " << bad;
    }
  // Finite channels whose sum overflows are rejected too (the film sums in double, but such a
  // value is a bug upstream).
  EXPECT_FALSE(isValidRadiance(Color3(3e38f, 3e38f, 0.f)));
}

}  // namespace
}  // namespace penumbra
