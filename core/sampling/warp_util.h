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

// Shirley-Chiu concentric map in polar form: the point is r (cos θ, sin θ) with a signed radius
// |r| <= 1 - 2^-24 (inputs are centred, so the rim is never reached) and θ given in turns (θ / 2π).
inline void concentricPolar(Vec2 sample, float& r, float& thetaTurns) {
  float a = centredSample(sample.x), b = centredSample(sample.y);
  if (a == 0.f && b == 0.f) {  // not reachable from grid inputs; avoids 0/0
    r = 0.f;
    thetaTurns = 0.f;
  } else if (std::fabs(a) > std::fabs(b)) {
    r = a;
    thetaTurns = 0.125f * (b / a);
  } else {
    r = b;
    thetaTurns = 0.25f - 0.125f * (a / b);
  }
}

// The point r (cos θ, sin θ) of concentricPolar.
inline Vec2 concentricPoint(Vec2 sample) {
  float r, thetaTurns;
  concentricPolar(sample, r, thetaTurns);
  const SinCos sc = sinCosTurns(thetaTurns);
  return Vec2(r * sc.cos, r * sc.sin);
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
