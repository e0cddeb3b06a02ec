// Small helpers shared by the warp implementations (not part of the public warp API).
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math/sincos_turns.h"
#include "core/math/vec.h"

namespace penumbra {

// Maps a canonical sample u in [0, 1 - 2^-24] to 2u - 1 + 2^-24, symmetric in
// [-(1 - 2^-24), 1 - 2^-24]. Samplers hand out the grid k 2^-24; this is the centre of the grid
// cell (so it is, if anything, less biased than 2u - 1) and it never reaches the rim (|a| = 1) or
// the exact centre a = 0 of the concentric map. Exact in float for grid inputs.
inline float centredSample(float u) {
  return (2.f * u - 1.f) + 0x1p-24f;
}
inline float centredSampleInverse(float a) {
  return std::clamp(0.5f * (a - 0x1p-24f + 1.f), 0.f, kOneMinusEpsilon);
}

inline float clampUnit(float u) {
  return std::clamp(u, 0.f, kOneMinusEpsilon);
}

// atan2(y, x) / 2pi wrapped to [0, 1).
inline float phiToUnit(float y, float x) {
  float u = std::atan2(y, x) * kInv2Pi;
  if (u < 0.f) u += 1.f;
  return u >= 1.f ? 0.f : u;
}

// Membership tests with a few ulps of slack, so samples whose coordinates were rounded outward by
// one ulp still count as inside; points measurably outside get density exactly 0.
inline constexpr float kSupportSlack = 0x1p-20f;
inline bool insideUnitDisk(Vec2 p) {
  return p.x * p.x + p.y * p.y <= 1.f + kSupportSlack;
}

// Shirley-Chiu concentric map: the point r (cos θ, sin θ) with θ = π/4 · b/a where |a| > |b|, else
// π/2 − π/4 · a/b, for the centred sample (a, b); |r| = max(|a|, |b|) <= 1 - 2^-24 (the rim is never
// reached) is returned in `rho`. θ's two branches differ only by swapping sin and cos, so the
// unpredictable choice is made by selects and the trigonometry is one polynomial pair.
inline Vec2 concentricPoint(Vec2 sample, float& rho) {
  const float a = centredSample(sample.x), b = centredSample(sample.y);
  const bool aDominant = std::fabs(a) > std::fabs(b);
  const float r = aDominant ? a : b;
  if (r == 0.f) {  // a == b == 0: not reachable from grid inputs; avoids 0/0
    rho = 0.f;
    return Vec2(0.f);
  }
  const SinCos sc = sinCosQuarterPi(kPiOver4 * ((aDominant ? b : a) / r));
  rho = std::fabs(r);
  return Vec2(r * (aDominant ? sc.cos : sc.sin), r * (aDominant ? sc.sin : sc.cos));
}

// 1 - z of a unit direction without cancellation near the pole: (x^2 + y^2) / (1 + z) for z > 0.
inline float oneMinusCosTheta(const Vec3& v) {
  return v.z > 0.f ? (v.x * v.x + v.y * v.y) / (1.f + v.z) : 1.f - v.z;
}

// Unit direction with 1 - cos(theta) = w (w in [0, 2]) and azimuth 2 pi u; sin(theta) comes from
// w (2 - w), which keeps full relative precision for tiny w.
inline Vec3 directionFromOneMinusCos(float w, float u) {
  float sinTheta = std::sqrt(std::max(w * (2.f - w), 0.f));
  const SinCos phi = sinCosTurns(u);
  return Vec3(sinTheta * phi.cos, sinTheta * phi.sin, 1.f - w);
}

}  // namespace penumbra
