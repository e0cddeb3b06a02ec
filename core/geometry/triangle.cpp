#include "core/geometry/triangle.h"

#include <cmath>
#include <limits>

namespace penumbra {
void fillTriangleHit(const TriangleMesh& mesh, uint32_t primId, const TriangleIntersection& isect,
                     uint32_t objectId, SurfaceHit& hit) {
  const glm::uvec3 tri = mesh.triangles[primId];
  const Vec3& p0 = mesh.positions[tri.x];
  const Vec3& p1 = mesh.positions[tri.y];
  const Vec3& p2 = mesh.positions[tri.z];
  hit.t = isect.t;
  // From the barycentrics: accurate to the rounding of the vertices' magnitude (see offsetScale).
  hit.p = isect.b0 * p0 + isect.b1 * p1 + isect.b2 * p2;
  Vec3 ng = glm::cross(p1 - p0, p2 - p0);
  const float len = glm::length(ng);
  if (len > 0.f && std::isfinite(len)) {
    ng /= len;
  } else {  // degenerate or overflowing: recompute in double
    const DVec3 nd = glm::cross(DVec3(p1) - DVec3(p0), DVec3(p2) - DVec3(p0));
    const double l = glm::length(nd);
    ng = l > 0.0 ? Vec3(nd / l) : Vec3(0, 0, 1);
  }
  hit.ng = ng;
  hit.ns = ng;
  if (!mesh.normals.empty()) {
    const Vec3 ns =
        isect.b0 * mesh.normals[tri.x] + isect.b1 * mesh.normals[tri.y] + isect.b2 * mesh.normals[tri.z];
    const float l = glm::length(ns);
    if (l > 0.f && std::isfinite(l)) hit.ns = ns / l;
  }
  const Vec3 m = glm::max(absVec(p0), glm::max(absVec(p1), absVec(p2)));
  hit.offsetScale = std::max(maxComponent(m), maxAbsComponent(hit.p));
  hit.objectId = objectId;
  hit.primId = primId;
}

void projectOntoPlane(const TrianglePlane& plane, SurfaceHit& hit) {
  const DVec3 p(hit.p);
  hit.p = Vec3(p - plane.normal * (glm::dot(plane.normal, p) - plane.offset));
  // The brute-force triangle test rejects hits within its own rounding error of t (pbrt-v4's
  // conservative t), so an origin offset relative to |p| cannot re-hit this triangle.
  hit.offsetScale = maxAbsComponent(hit.p);
}

TrianglePlane trianglePlane(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const DVec3 d0(p0), d1(p1), d2(p2);
  DVec3 n = glm::cross(d1 - d0, d2 - d0);
  const double len = glm::length(n);
  if (!(len > 0.0) || !std::isfinite(len)) return TrianglePlane{DVec3(0.0), 0.0};
  n /= len;
  return TrianglePlane{n, glm::dot(n, (d0 + d1 + d2) / 3.0)};
}

}  // namespace penumbra
