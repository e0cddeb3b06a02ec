#include "core/math/sincos_turns.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

namespace penumbra {
namespace {

// Error in units of 2^-24 · max(|truth|, 2^-24): about one float ulp of the true value, with a floor
// near zero crossings where the double reference itself carries ~1e-16 of angle rounding.
double ulpError(float got, double truth) {
  return std::fabs(got - truth) / (0x1p-24 * std::max(std::fabs(truth), 0x1p-24));
}

TEST(SinCosTurns, WithinThreeUlpsOnEverySamplerValue) {
  // Every value a sampler can hand out: k · 2^-24 for k < 2^24.
  double worstSin = 0.0, worstCos = 0.0, worstNorm = 0.0;
  for (uint32_t k = 0; k < (1u << 24); k += 7) {
    const float u = static_cast<float>(k) * 0x1p-24f;
    const SinCos sc = sinCosTurns(u);
    const double angle = (2.0 * kPiD) * u;
    worstSin = std::max(worstSin, ulpError(sc.sin, std::sin(angle)));
    worstCos = std::max(worstCos, ulpError(sc.cos, std::cos(angle)));
    worstNorm = std::max(worstNorm, std::fabs(double(sc.sin) * sc.sin + double(sc.cos) * sc.cos - 1.0));
  }
  EXPECT_LT(worstSin, 3.0);
  EXPECT_LT(worstCos, 3.0);
  EXPECT_LT(worstNorm, 3e-7);
}

TEST(SinCosTurns, ExactAtQuarterTurnsAndSymmetric) {
  const float quarters[] = {0.f, 0.25f, 0.5f, 0.75f, 1.f, -0.25f};
  const float sines[] = {0.f, 1.f, 0.f, -1.f, 0.f, -1.f};
  const float cosines[] = {1.f, 0.f, -1.f, 0.f, 1.f, 0.f};
  for (int i = 0; i < 6; ++i) {
    const SinCos sc = sinCosTurns(quarters[i]);
    EXPECT_EQ(std::fabs(sc.sin), std::fabs(sines[i])) << quarters[i];
    EXPECT_EQ(sc.sin == 0.f ? 0.f : sc.sin, sines[i]) << quarters[i];
    EXPECT_EQ(sc.cos == 0.f ? 0.f : sc.cos, cosines[i]) << quarters[i];
  }
  for (float t : {0.01f, 0.1f, 0.3f, 0.49f}) {
    EXPECT_EQ(sinCosTurns(-t).sin, -sinCosTurns(t).sin);
    EXPECT_EQ(sinCosTurns(-t).cos, sinCosTurns(t).cos);
  }
}

TEST(SinCosTurns, NegativeAndLargeArguments) {
  for (float t : {-3.3f, -0.6f, 1.7f, 12.125f, 1000.37f}) {
    const SinCos sc = sinCosTurns(t);
    const double angle = (2.0 * kPiD) * double(t);
    EXPECT_NEAR(sc.sin, std::sin(angle), 4e-7) << t;
    EXPECT_NEAR(sc.cos, std::cos(angle), 4e-7) << t;
  }
}

TEST(SinCosTurns, NonFiniteInputsGiveNaN) {
  EXPECT_TRUE(std::isnan(sinCosTurns(NAN).sin));
  EXPECT_TRUE(std::isnan(sinCosTurns(INFINITY).cos));
}

}  // namespace
}  // namespace penumbra
