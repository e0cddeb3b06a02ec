// The circular segment: the part of the unit disk beyond a chord. A chord at distance cos β from the
// centre cuts off a segment of area g(β) = β − sin β cos β (β ∈ [0, π] the half angle it subtends at
// the centre; g(π/2) = π/2 is the half disk, g(π) = π the disk). Its inverse is what the parallel map
// of a disk cut by a chord needs: the position of the chord that cuts off a given area.
#pragma once

namespace penumbra {

struct SinCosD {
  double sin, cos;
};

// sin and cos of β ∈ [0, π/2] by polynomials (Chebyshev economisations of the Taylor series on
// [−π/2, π/2]), within 4e-16 of the true values.
SinCosD sinCosHalfPi(double beta);

// g(β) = β − sin β cos β for β ∈ [0, π], given sin β and cos β; relatively accurate for small β too
// (where the difference would cancel: a series below β = 1/4).
double segmentArea(double beta, SinCosD sc);

// sin β and cos β of the β ∈ [0, π] with g(β) = area, area ∈ [0, π] (clamped). Non-iterative: a first
// guess β₀ = w P(w²), w = ∛(3 area / 2) (g(β) ≈ 2β³/3 for small β; P a degree-6 fit of β / w, relative
// error below 2.3e-6; the cube root from the bits and one Halley step, within 2.1e-5), then one Halley
// step on g, which cubes the guess's relative error (times ~(2/3) for small β): g at the returned angle
// is within 5e-13 of the area, relative (4e-14 measured; swept from 1e-300 to π in
// circular_segment_test.cpp). Areas above π/2 by symmetry, g(π − β) = π − g(β).
SinCosD segmentAngle(double area);

}  // namespace penumbra
