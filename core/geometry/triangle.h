// Watertight ray-triangle intersection (Woop, Benthin, Wald 2013, as in pbrt-v4) and hit filling.
#pragma once

#include <cstdint>

#include "core/geometry/ray.h"
#include "core/geometry/surface_hit.h"
#include "core/geometry/triangle_mesh.h"

namespace penumbra {

struct TriangleIntersection {
  float t;
  float b0, b1, b2;  // barycentrics of p0, p1, p2
};

// Hit of the ray with triangle (p0, p1, p2) for ray.tMin < t < tMax (tMax passed separately so the
// caller can shrink it while looping). Watertight: a ray through an edge or vertex shared by two
// triangles hits at least one of them; edge tests that round to exactly 0 are redone in double.
// A hit is reported only if t is conservatively positive (pbrt-v4 error bound), which together with
// offsetRayOrigin prevents self-intersection. Back faces are hit too (no culling).
bool intersectTriangle(const Ray& ray, float tMax, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                       TriangleIntersection& out);

// Fills hit data for triangle `primId` of `mesh`: p from the barycentrics (accuracy relative to the
// vertex magnitudes, independent of the ray length), ng = normalize(cross(p1 − p0, p2 − p0)),
// ns = normalised interpolated vertex normals when the mesh has them (ng if they degenerate).
void fillTriangleHit(const TriangleMesh& mesh, uint32_t primId, const TriangleIntersection& isect,
                     uint32_t objectId, SurfaceHit& hit);

}  // namespace penumbra
