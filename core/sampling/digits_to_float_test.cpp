#include "core/sampling/digits_to_float.h"

#include <gtest/gtest.h>

#include <bit>

#include "core/math/vec.h"
#include "core/sampling/owen_scramble.h"
#include "core/sampling/rng.h"

namespace penumbra {
namespace {

// Every value of the 24 digits that reach the float, each with other bits above them: the same bits
// as reversing and converting (so the Sobol' samplers' values do not depend on which is used).
TEST(DigitsToFloat, EqualsReversalThenConversionForEveryTop24Digits) {
  int mismatches = 0;
  for (uint32_t low = 0; low < (1u << 24); ++low) {
    const uint32_t digits = low | (static_cast<uint32_t>(mix64(low)) << 24);
    const float expected = bitsToUnitFloat(reverseBits32(digits));
    if (std::bit_cast<uint32_t>(digitsToUnitFloat(digits)) != std::bit_cast<uint32_t>(expected) &&
        ++mismatches <= 5)
      ADD_FAILURE() << "digits " << std::hex << digits << ": " << digitsToUnitFloat(digits) << " vs "
                    << expected;
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(DigitsToFloat, RangeEnds) {
  EXPECT_EQ(digitsToUnitFloat(0u), 0.f);
  EXPECT_EQ(digitsToUnitFloat(~0u), kOneMinusEpsilon);
  EXPECT_EQ(digitsToUnitFloat(1u), 0.5f);  // digit 1 = bit 0
}

}  // namespace
}  // namespace penumbra
