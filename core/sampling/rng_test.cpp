#include "core/sampling/rng.h"

#include <gtest/gtest.h>

#include "core/math/vec.h"

namespace penumbra {
namespace {

TEST(Rng, UnitFloatNeverReachesOne) {
  EXPECT_EQ(bitsToUnitFloat(0xffffffffu), kOneMinusEpsilon);
  EXPECT_LT(bitsToUnitFloat(0xffffffffu), 1.f);
  EXPECT_EQ(bitsToUnitFloat(0u), 0.f);
  EXPECT_EQ(bitsToUnitFloat(0x80000000u), 0.5f);
}

TEST(Rng, FloatsInUnitIntervalWithUniformMoments) {
  Rng rng(42, 7);
  double sum = 0.0, sum2 = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    float u = rng.nextFloat();
    ASSERT_GE(u, 0.f);
    ASSERT_LT(u, 1.f);
    sum += u;
    sum2 += double(u) * u;
  }
  EXPECT_NEAR(sum / n, 0.5, 0.005);
  EXPECT_NEAR(sum2 / n, 1.0 / 3.0, 0.005);
  for (int i = 0; i < 1000; ++i) {
    double d = rng.nextDouble();
    ASSERT_GE(d, 0.0);
    ASSERT_LT(d, 1.0);
  }
}

TEST(Rng, DeterministicPerSeedAndStream) {
  Rng a(1, 2), b(1, 2), c(1, 3), d(2, 2);
  int sameC = 0, sameD = 0;
  for (int i = 0; i < 100; ++i) {
    uint32_t x = a.nextU32();
    ASSERT_EQ(x, b.nextU32());
    sameC += x == c.nextU32();
    sameD += x == d.nextU32();
  }
  EXPECT_LT(sameC, 3);
  EXPECT_LT(sameD, 3);
}

TEST(Rng, AdvanceSkipsAhead) {
  Rng a(9, 1), b(9, 1);
  for (int i = 0; i < 37; ++i) a.nextU32();
  b.advance(37);
  EXPECT_EQ(a.nextU32(), b.nextU32());
}

}  // namespace
}  // namespace penumbra
