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
  // Interpolate in double and project onto the triangle's plane, so that p lies on the surface to
  // within one rounding of its own magnitude (not of the triangle's): ray offsets can then be
  // relative to |p| and contact shadows next to large triangles survive.
  const DVec3 d0(p0), d1(p1), d2(p2);
  DVec3 pd = double(isect.b0) * d0 + double(isect.b1) * d1 + double(isect.b2) * d2;
  const DVec3 nd = glm::cross(d1 - d0, d2 - d0);
  const double nn = glm::dot(nd, nd);
  if (nn > 0.0 && std::isfinite(nn)) pd -= nd * (glm::dot(pd - d0, nd) / nn);
  hit.p = Vec3(pd);
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
  // The triangle test rejects hits within its own rounding error of t (pbrt-v4's conservative t),
  // so an origin offset relative to |p| cannot re-hit this triangle. SceneGeometry widens this for
  // Embree, whose test has no such bound.
  hit.offsetScale = maxComponent(glm::abs(hit.p));
  hit.objectId = objectId;
  hit.primId = primId;
}

}  // namespace penumbra
