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
  const Vec3 m = glm::max(glm::abs(p0), glm::max(glm::abs(p1), glm::abs(p2)));
  hit.offsetScale = std::max(maxComponent(m), maxComponent(glm::abs(hit.p)));
  hit.objectId = objectId;
  hit.primId = primId;
}

}  // namespace penumbra
