// The circular segment: the part of the unit disk beyond a chord. A chord at distance cos β from the
// centre cuts off a segment of area g(β) = β − sin β cos β (β ∈ [0, π] the half angle it subtends at
// the centre; g(π/2) = π/2 is the half disk, g(π) = π the disk). Its inverse is what the parallel map
// of a disk cut by a chord needs: the position of the chord that cuts off a given area.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace penumbra {

struct SinCosD {
  double sin, cos;
};

namespace circular_segment_detail {

inline constexpr double kSegmentPi = 3.14159265358979323846;
inline constexpr double kSegmentHalfPi = 1.57079632679489661923;

// ∛t for normal t > 0 within 2.1e-5 relative: the exponent divided by three on the bits (a guess within
// a few per cent), then one Halley step r (r³ + 2t) / (2r³ + t). std::cbrt costs ~140 instructions.
inline double approximateCbrt(double t) {
  const uint64_t bits = std::bit_cast<uint64_t>(t) / 3 + 0x2a9f7893782da1ceull;
  const double r = std::bit_cast<double>(bits), r3 = r * r * r;
  return r * ((r3 + 2.0 * t) / (2.0 * r3 + t));  // the ratio first: r (r³ + 2t) underflows for t < 1e-216
}

}  // namespace circular_segment_detail

// sin and cos of β ∈ [0, π/2] by polynomials (Chebyshev economisations of the Taylor series on
// [−π/2, π/2]), within 4e-16 of the true values.
inline SinCosD sinCosHalfPi(double x) {
  const double x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
  // Estrin's scheme: short dependency chains.
  const double s01 = -0.166666666666666629659 + x2 * 0.00833333333333299321188;
  const double s23 = -0.000198412698411593773143 + x2 * 2.75573192045707538654e-06;
  const double s45 = -2.50521063803320396541e-08 + x2 * 1.60589186111811444465e-10;
  const double s67 = -7.64251091766084167619e-13 + x2 * 2.71665816482462536047e-15;
  const double s = x + x * x2 * ((s01 + x4 * s23) + x8 * (s45 + x4 * s67));
  const double c01 = 0.0416666666666666574148 + x2 * -0.00138888888888885294638;
  const double c23 = 2.48015873014926947618e-05 + x2 * -2.75573192096606129619e-07;
  const double c45 = 2.0876755667001344682e-09 + x2 * -1.14706701822545502061e-11;
  const double c67 = 4.77687261509173744093e-14 + x2 * -1.51198607905463560669e-16;
  const double c = 1.0 - 0.5 * x2 + x4 * ((c01 + x4 * c23) + x8 * (c45 + x4 * c67));
  return {s, c};
}

// g(β) = β − sin β cos β for β ∈ [0, π], given sin β and cos β; relatively accurate for small β too
// (where the difference would cancel: a series below β = 1/4).
inline double segmentArea(double beta, SinCosD sc) {
  if (beta >= 0.25) return beta - sc.sin * sc.cos;
  // Σ (−1)^(k+1) 4^k β^(2k+1) / (2k+1)!, k = 1..8 (truncated below 1e-18 of the sum at β = 1/4).
  const double b2 = beta * beta, b4 = b2 * b2;
  const double p01 = 0.666666666666666629659 + b2 * -0.133333333333333331483;
  const double p23 = 0.0126984126984126984017 + b2 * -0.00070546737213403884828;
  const double p45 = 2.56533589866923215092e-05 + b2 * -6.57778435556213282442e-07;
  const double p67 = 1.25291130582135871988e-08 + b2 * -1.84251662620788037918e-10;
  return beta * b2 * ((p01 + b4 * p23) + (b4 * b4) * (p45 + b4 * p67));
}

// sin β and cos β of the β ∈ [0, π] with g(β) = area, area ∈ [0, π] (clamped). Non-iterative: a first
// guess β₀ = w P(w²), w = ∛(3 area / 2) (g(β) ≈ 2β³/3 for small β; P a degree-6 fit of β / w, relative
// error below 2.3e-6; the cube root from the bits and one Halley step, within 2.1e-5), then one Halley
// step on g, which cubes the guess's relative error (times ~(2/3) for small β): g at the returned angle
// is within 5e-13 of the area, relative (4e-14 measured; swept from 1e-300 to π in
// circular_segment_test.cpp). Areas above π/2 by symmetry, g(π − β) = π − g(β).
// Inlined: it runs once per sample, and its callers' branches fold into it.
[[gnu::always_inline]] inline SinCosD segmentAngle(double area) {
  using namespace circular_segment_detail;
  if (!(area > 0.0)) return {0.0, 1.0};
  if (!(area < kSegmentPi)) return {0.0, -1.0};
  const bool far = area > kSegmentHalfPi;
  const double t = far ? kSegmentPi - area : area;  // g(π − β) = π − g(β)
  // First guess (above): β₀ = w P(w²), w = ∛(3t/2), P fitted on w² ∈ [0, (3π/4)^(2/3)].
  // Below 1e-280 the sine's powers in Halley's step would underflow; there β = ∛(3t/2) to 1e-186.
  if (t < 1e-280) {
    const double beta = std::cbrt(1.5 * t);
    return {beta, far ? -1.0 : 1.0};
  }
  const double w = approximateCbrt(1.5 * t);
  const double s = w * w, s2 = s * s;
  const double p =
      (1.0000011687077255 + s * 0.066602351422516998) +
      s2 * ((0.011992806966590205 + s * 0.00073670834904429258) +
            s2 * ((0.0032669856132814842 + s * -0.0016490027414180583) + s2 * 0.00056507748318391289));
  const double beta0 = std::min(w * p, kSegmentHalfPi);
  const SinCosD sc = sinCosHalfPi(beta0);
  // Halley's step on f = g(β) − t, f' = 2 sin²β, f'' = 4 sin β cos β: −2 f f' / (2 f'² − f f'') =
  // −f sin β / (2 sin³β − f cos β).
  const double f = segmentArea(beta0, sc) - t;
  const double denominator = 2.0 * sc.sin * sc.sin * sc.sin - f * sc.cos;
  const double delta = denominator > 0.0 ? -(f / denominator) * sc.sin : 0.0;  // f sin β could underflow
  // Rotate (sin, cos) by δ: |δ| ≤ 4e-5 (the guess's error), so two Taylor terms each are exact to 1e-19.
  const double delta2 = delta * delta;
  const double sinDelta = delta - delta * delta2 * (1.0 / 6.0), cosDelta = 1.0 - 0.5 * delta2;
  const double sinBeta = std::clamp(sc.sin * cosDelta + sc.cos * sinDelta, 0.0, 1.0);
  const double cosBeta = std::clamp(sc.cos * cosDelta - sc.sin * sinDelta, 0.0, 1.0);
  return {sinBeta, far ? -cosBeta : cosBeta};
}

}  // namespace penumbra
