// Robust float helpers: square roots that never see a negative, 1 - cos from sin^2, ray origin offsets,
// the validity of a radiance sample.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math/vec.h"

namespace penumbra {

inline float safeSqrt(float x) {
  return std::sqrt(std::max(x, 0.f));
}
inline double safeSqrt(double x) {
  return std::sqrt(std::max(x, 0.0));
}

// 1 - sqrt(1 - s2) without cancellation for small s2 (= s2 / (1 + sqrt(1 - s2))).
inline float oneMinusSqrtOneMinus(float s2) {
  return s2 / (1.f + safeSqrt(1.f - s2));
}
inline double oneMinusSqrtOneMinus(double s2) {
  return s2 / (1.0 + safeSqrt(1.0 - s2));
}

inline bool isFinite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// A radiance sample fit to accumulate: every channel non-negative and finite. NaN, Inf or a negative
// value is a bug somewhere; callers count it and drop it.
inline bool isValidRadiance(const Color3& L) {
  return L.x >= 0.f && L.y >= 0.f && L.z >= 0.f && std::isfinite(L.x + L.y + L.z);
}

// Relative offset used to move ray origins off surfaces: 16 ulps of the magnitude of the numbers the
// hit point came from, so the same scene at 1e-4 and 1e4 units behaves identically. Small enough for
// a shading point 1e-6 r outside a sphere light; large enough that spheres (re-projected hit points)
// and Embree triangles do not re-hit themselves; brute-force triangles also reject t within their
// rounding error (see triangle.h).
inline constexpr float kRayOffsetScale = 0x1p-20f;  // ~9.5e-7: 16 float ulps

// Offsets p along the geometric normal ng (towards the side of w) by an amount proportional to
// `scale`, the magnitude of the coordinates that produced p (hit point and the shape's extent).
inline Vec3 offsetRayOrigin(const Vec3& p, const Vec3& ng, float scale, const Vec3& w) {
  float d = kRayOffsetScale * scale;
  Vec3 offset = ng * d;
  if (glm::dot(w, ng) < 0.f) offset = -offset;
  return p + offset;
}

}  // namespace penumbra
