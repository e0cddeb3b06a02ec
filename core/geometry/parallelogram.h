// Two triangles of a mesh that form a planar parallelogram (the ubiquitous two-triangle `plane.obj`
// floor), intersected as one primitive: a plane test plus two dual-vector dot products, instead of
// two watertight triangle tests. Only used by the brute-force path of SceneGeometry, and only when
// the merge changes nothing visible: same plane, same winding, equal vertex normals, and outer edges
// that no other triangle of the mesh shares (so no crack can open against a neighbour).
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "core/geometry/ray.h"
#include "core/geometry/surface_hit.h"
#include "core/geometry/triangle_mesh.h"

namespace penumbra {

// The points p0 + u·e1 + v·e2 with u, v in [0, 1]. Triangle `primLow` is the half u + v <= 1.
struct Parallelogram {
  Vec3 p0;
  Vec3 n;             // unit geometric normal, the source triangles' winding
  float planeOffset;  // n · x for x on the plane
  Vec3 du, dv;        // dual vectors: u = du · (x − p0), v = dv · (x − p0) for x on the plane
  Vec3 ns;            // shading normal (the common vertex normal, or n)
  uint32_t mesh, primLow, primHigh;
};

namespace detail {
constexpr float kParallelogramGamma7 = 7.f * std::numeric_limits<float>::epsilon() * 0.5f /
                                       (1.f - 7.f * std::numeric_limits<float>::epsilon() * 0.5f);
constexpr float kParallelogramGamma3 = 3.f * std::numeric_limits<float>::epsilon() * 0.5f /
                                       (1.f - 3.f * std::numeric_limits<float>::epsilon() * 0.5f);
}  // namespace detail

// Hit for ray.tMin < t < tMax; (u, v) locate it. Conservative like the triangle test: no hit when the
// origin's side of the plane, or the ray's direction across it, is within float rounding. A ray that
// starts on the plane (a shadow or AO ray leaving it) therefore never re-hits it: for a plane, t = 0
// is the only hit such a ray could have.
inline bool intersectParallelogram(const Parallelogram& q, const Ray& ray, float tMax, float& t, float& u,
                                   float& v) {
  const float denom = glm::dot(q.n, ray.d);
  const float h = glm::dot(q.n, ray.o) - q.planeOffset;  // signed distance of the origin
  const Vec3 nd = absVec(q.n * ray.d), no = absVec(q.n * ray.o);
  if (!(std::abs(denom) > detail::kParallelogramGamma3 * (nd.x + nd.y + nd.z))) return false;
  if (!(std::abs(h) > detail::kParallelogramGamma7 * (no.x + no.y + no.z + std::abs(q.planeOffset))))
    return false;
  t = -h / denom;
  if (!(t > ray.tMin && t < tMax)) return false;
  const Vec3 rel = (ray.o - q.p0) + t * ray.d;
  u = glm::dot(q.du, rel);
  v = glm::dot(q.dv, rel);
  return u >= 0.f && u <= 1.f && v >= 0.f && v <= 1.f;
}

// Hit data for a t from intersectParallelogram: p is o + t·d moved onto the plane in double, so it is
// accurate to its own magnitude (offsetScale = |p|, as for brute-force triangles).
void fillParallelogramHit(const Parallelogram& q, const Ray& ray, float t, float u, float v,
                          uint32_t objectId, SurfaceHit& hit);

// Splits mesh `meshIndex` into parallelograms (pairs of its triangles that qualify, see the header
// comment) and the triangles left over (indices into mesh.triangles).
void pairParallelograms(const TriangleMesh& mesh, uint32_t meshIndex, std::vector<Parallelogram>& quads,
                        std::vector<uint32_t>& leftover);

}  // namespace penumbra
