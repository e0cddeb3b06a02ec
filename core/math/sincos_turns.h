// sin and cos of an angle given in turns (2π·t), for the warps' azimuths. Cheaper than libm's
// sincosf (which must reduce any float argument) because reduction by a quarter turn is exact here:
// 4t − round(4t) is computed without rounding for |t| < 2^20, leaving |x| ≤ π/4 for the polynomials.
// Accuracy: within 2 float ulps of the true value (sincos_turns_test.cpp), sin² + cos² = 1 to ~1e-7.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "core/math/vec.h"

namespace penumbra {

struct SinCos {
  float sin, cos;
};

// Cephes sinf / cosf minimax coefficients for |x| <= π/4 (the packet kernels evaluate the same
// polynomials lane by lane).
struct SinCosCoefficients {
  static constexpr float kSin1 = -1.6666654611e-1f, kSin2 = 8.3321608736e-3f, kSin3 = -1.9515295891e-4f;
  static constexpr float kCos1 = 4.166664568298827e-2f, kCos2 = -1.388731625493765e-3f,
                         kCos3 = 2.443315711809948e-5f;
  // Round to nearest by adding and subtracting 1.5·2^23.
  static constexpr float kRoundingBias = 0x1.8p23f;
};

// sin and cos of |x| <= π/4: the polynomials alone.
inline SinCos sinCosQuarterPi(float x) {
  using K = SinCosCoefficients;
  const float x2 = x * x;
  const float s = x + x * x2 * (K::kSin1 + x2 * (K::kSin2 + x2 * K::kSin3));
  const float c = 1.f - 0.5f * x2 + x2 * x2 * (K::kCos1 + x2 * (K::kCos2 + x2 * K::kCos3));
  return {s, c};
}

inline SinCos sinCosTurns(float turns) {
  const float quarters = 4.f * turns;  // exact: a power-of-two scale
  // Round to nearest by the 1.5·2^23 trick (std::nearbyint is a libm call without SSE4.1); beyond
  // 2^22 quarters every float is already (nearly) whole and no precision is left to keep anyway.
  constexpr float kRoundingBias = SinCosCoefficients::kRoundingBias;
  const float q = std::fabs(quarters) < 0x1p22f ? (quarters + kRoundingBias) - kRoundingBias : quarters;
  const SinCos r = sinCosQuarterPi((quarters - q) * kPiOver2);  // quarters − q is exact
  const float s = r.sin, c = r.cos;
  // Rotate by q quarter turns: (sin, cos) of x + q·π/2. Done on the bits, without branches: the
  // quadrant of a random azimuth is unpredictable. std::max/min (not fmax/fmin, which are libm calls
  // without SSE4.1) clamp the conversion into range; NaN maps to the bound (x is NaN then anyway).
  const auto quadrant = static_cast<uint32_t>(static_cast<int32_t>(std::min(0x1p24f, std::max(-0x1p24f, q))));
  const uint32_t swap = 0u - (quadrant & 1u);  // all ones in odd quadrants
  const uint32_t sBits = std::bit_cast<uint32_t>(s), cBits = std::bit_cast<uint32_t>(c);
  const uint32_t sinBits = ((sBits & ~swap) | (cBits & swap)) ^ ((quadrant & 2u) << 30);
  const uint32_t cosBits = ((cBits & ~swap) | (sBits & swap)) ^ (((quadrant + 1u) & 2u) << 30);
  return {std::bit_cast<float>(sinBits), std::bit_cast<float>(cosBits)};
}

}  // namespace penumbra
