// atan2 from +, −, ×, ÷ and comparisons alone, in a fixed order, so that SIMD lanes (packet_math-inl.h's
// portableAtan2Lanes) compute it bit for bit where libm's atan2 could only be called lane by lane: the
// projected polygon's map calls it in every Newton step of its inversion. Within 2.5 ulp of the exact
// value for finite arguments, with atan2's signs and zeros (portable_atan2_test.cpp); a non-finite
// argument goes to std::atan2.
// Method: |y| and |x| ordered into a ratio t ≤ 1; above tan(π/8), atan t = π/4 + atan((n − d)/(n + d));
// atan z = z + z³ P(z²) with P a Chebyshev fit of degree 10 on z² ≤ tan²(π/8) (tools/fit_atan2.py); the
// octant's multiple of π/4 added last, in two parts, so that its rounding does not dominate.
#pragma once

#include <cmath>

namespace penumbra {

struct PortableAtan2 {
  // P's coefficients, highest degree first.
  static constexpr double kP[11] = {-0.01917688711906226, 0.03923165829558719,  -0.0508544973794026,
                                    0.0585814891280221,   -0.06664511447381948, 0.07692183190826087,
                                    -0.09090904578123903, 0.11111111015256361,  -0.14285714284666542,
                                    0.1999999999999552,   -0.3333333333333333};
  static constexpr double kTanPiOver8 = 0.41421356237309503;
  // π, π/2 and π/4 as a double and the rest.
  static constexpr double kPi = 3.141592653589793, kPiLow = 1.2246467991473532e-16;
  static constexpr double kPiOver2 = 1.5707963267948966, kPiOver2Low = 6.123233995736766e-17;
  static constexpr double kPiOver4 = 0.7853981633974483, kPiOver4Low = 3.061616997868383e-17;

  // z + z³ P(z²) − z: the polynomial's part of atan z.
  static double tail(double z) {
    const double s = z * z;
    double p = kP[0];
    for (int i = 1; i < 11; ++i) p = p * s + kP[i];
    return z * (s * p);
  }
};

inline double portableAtan2(double y, double x) {
  using K = PortableAtan2;
  if (!(std::isfinite(x) && std::isfinite(y))) return std::atan2(y, x);
  const double ax = std::fabs(x), ay = std::fabs(y);
  const bool swap = ay > ax;
  const double num = swap ? ax : ay, den = swap ? ay : ax;
  const bool reduced = num > K::kTanPiOver8 * den;
  double z = reduced ? (num - den) / (num + den) : num / den;
  if (!(den > 0.0)) z = 0.0;  // both zero
  const double tail = K::tail(z);
  // The result is base + sign · (z + tail), base = (high, low) the octant's multiple of π/4.
  double high = reduced ? K::kPiOver4 : 0.0, low = reduced ? K::kPiOver4Low : 0.0, sign = 1.0;
  if (swap) {  // π/2 − the angle
    high = K::kPiOver2 - high;
    low = K::kPiOver2Low - low;
    sign = -sign;
  }
  if (std::signbit(x)) {  // π − the angle
    high = K::kPi - high;
    low = K::kPiLow - low;
    sign = -sign;
  }
  return std::copysign(high + (sign * z + (low + sign * tail)), y);
}

}  // namespace penumbra
