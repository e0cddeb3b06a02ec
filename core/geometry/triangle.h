// Watertight ray-triangle intersection (Woop, Benthin, Wald 2013, as in pbrt-v4) and hit filling.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "core/geometry/ray.h"
#include "core/geometry/surface_hit.h"
#include "core/geometry/triangle_mesh.h"

namespace penumbra {

struct TriangleIntersection {
  float t;
  float b0, b1, b2;  // barycentrics of p0, p1, p2
};

// Per-ray set-up of the watertight test, computed once per ray and reused for every triangle:
// the axis kz of the largest |d| component and the shear that maps d to +z.
struct TriangleRay {
  Vec3 o;
  float sx, sy, sz;
  float tMin;
  int kx, ky, kz;

  explicit TriangleRay(const Ray& ray) : o(ray.o), tMin(ray.tMin) {
    const Vec3 a = absVec(ray.d);
    kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    kx = kz == 2 ? 0 : kz + 1;
    ky = kx == 2 ? 0 : kx + 1;
    sz = 1.f / ray.d[kz];
    sx = -ray.d[kx] * sz;
    sy = -ray.d[ky] * sz;
  }
};

namespace detail {
constexpr float gammaN(int n) {
  constexpr float eps = std::numeric_limits<float>::epsilon() * 0.5f;
  return (n * eps) / (1.f - n * eps);
}
template <int K>
inline float comp(const Vec3& v) {
  if constexpr (K == 0)
    return v.x;
  else if constexpr (K == 1)
    return v.y;
  else
    return v.z;
}
}  // namespace detail

// Hit with triangle (p0, p1, p2) for ray.tMin < t < tMax (tMax passed separately so loops can shrink
// it). KZ is the ray's kz (template so the permutation costs nothing; dispatch once per ray).
// Watertight: a ray through an edge or vertex shared by two triangles hits at least one of them;
// edge functions that round to exactly 0 are redone in double. A hit is reported only if t is
// conservatively positive (pbrt-v4 error bound), which together with offsetRayOrigin prevents
// self-intersection. Back faces are hit too (no culling).
template <int KZ>
inline bool intersectTriangleK(const TriangleRay& ray, float tMax, const Vec3& p0, const Vec3& p1,
                               const Vec3& p2, TriangleIntersection& out) {
  constexpr int KX = KZ == 2 ? 0 : KZ + 1;
  constexpr int KY = KX == 2 ? 0 : KX + 1;
  using detail::comp;
  const float ox = comp<KX>(ray.o), oy = comp<KY>(ray.o), oz = comp<KZ>(ray.o);
  float z0 = comp<KZ>(p0) - oz, z1 = comp<KZ>(p1) - oz, z2 = comp<KZ>(p2) - oz;
  const float x0 = (comp<KX>(p0) - ox) + ray.sx * z0, y0 = (comp<KY>(p0) - oy) + ray.sy * z0;
  const float x1 = (comp<KX>(p1) - ox) + ray.sx * z1, y1 = (comp<KY>(p1) - oy) + ray.sy * z1;
  const float x2 = (comp<KX>(p2) - ox) + ray.sx * z2, y2 = (comp<KY>(p2) - oy) + ray.sy * z2;

  float e0 = x1 * y2 - y1 * x2;
  float e1 = x2 * y0 - y2 * x0;
  float e2 = x0 * y1 - y0 * x1;
  if ((e0 == 0.f) | (e1 == 0.f) | (e2 == 0.f)) [[unlikely]] {
    e0 = static_cast<float>(double(x1) * y2 - double(y1) * x2);
    e1 = static_cast<float>(double(x2) * y0 - double(y2) * x0);
    e2 = static_cast<float>(double(x0) * y1 - double(y0) * x1);
  }
  // Bitwise | and &: one well-predicted branch instead of six data-dependent ones.
  const bool anyNegative = (e0 < 0.f) | (e1 < 0.f) | (e2 < 0.f);
  const bool anyPositive = (e0 > 0.f) | (e1 > 0.f) | (e2 > 0.f);
  if (anyNegative & anyPositive) return false;
  const float det = e0 + e1 + e2;
  if (det == 0.f) return false;

  z0 *= ray.sz;
  z1 *= ray.sz;
  z2 *= ray.sz;
  const float tScaled = e0 * z0 + e1 * z1 + e2 * z2;
  if (det < 0.f && (tScaled >= 0.f || tScaled < tMax * det)) return false;
  if (det > 0.f && (tScaled <= 0.f || tScaled > tMax * det)) return false;

  const float invDet = 1.f / det;
  const float t = tScaled * invDet;
  if (!(t < tMax) || !(t > ray.tMin)) return false;

  // Conservative check that t > 0 (pbrt-v4, 6.5.3): reject hits within the rounding error of t.
  using detail::gammaN;
  const float maxZt = std::max(std::abs(z0), std::max(std::abs(z1), std::abs(z2)));
  const float maxXt = std::max(std::abs(x0), std::max(std::abs(x1), std::abs(x2)));
  const float maxYt = std::max(std::abs(y0), std::max(std::abs(y1), std::abs(y2)));
  const float deltaZ = gammaN(3) * maxZt;
  const float deltaX = gammaN(5) * (maxXt + maxZt);
  const float deltaY = gammaN(5) * (maxYt + maxZt);
  const float deltaE = 2.f * (gammaN(2) * maxXt * maxYt + deltaY * maxXt + deltaX * maxYt);
  const float maxE = std::max(std::abs(e0), std::max(std::abs(e1), std::abs(e2)));
  const float deltaT = 3.f * (gammaN(3) * maxE * maxZt + deltaE * maxZt + deltaZ * maxE) * std::abs(invDet);
  if (t <= deltaT) return false;

  out.t = t;
  out.b0 = e0 * invDet;
  out.b1 = e1 * invDet;
  out.b2 = e2 * invDet;
  return true;
}

// Convenience form (sets up the ray each call).
inline bool intersectTriangle(const Ray& ray, float tMax, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                              TriangleIntersection& out) {
  const TriangleRay tr(ray);
  switch (tr.kz) {
    case 0:
      return intersectTriangleK<0>(tr, tMax, p0, p1, p2, out);
    case 1:
      return intersectTriangleK<1>(tr, tMax, p0, p1, p2, out);
    default:
      return intersectTriangleK<2>(tr, tMax, p0, p1, p2, out);
  }
}

// Fills hit data for triangle `primId` of `mesh`: p from the barycentrics (accuracy relative to the
// vertex magnitudes, independent of the ray length), ng = normalize(cross(p1 − p0, p2 − p0)),
// ns = normalised interpolated vertex normals when the mesh has them (ng if they degenerate).
void fillTriangleHit(const TriangleMesh& mesh, uint32_t primId, const TriangleIntersection& isect,
                     uint32_t objectId, SurfaceHit& hit);

// A triangle's plane in double precision: unit normal and offset (n . p = offset on the plane).
struct TrianglePlane {
  DVec3 normal;
  double offset;
};
TrianglePlane trianglePlane(const Vec3& p0, const Vec3& p1, const Vec3& p2);

// Moves hit.p onto the plane (in double) so that it is accurate to its own magnitude rather than the
// triangle's, and makes ray offsets relative to |p|: contact shadows next to large triangles survive.
// Only for hits of the conservative brute-force test (a degenerate plane leaves p unchanged).
void projectOntoPlane(const TrianglePlane& plane, SurfaceHit& hit);

}  // namespace penumbra
