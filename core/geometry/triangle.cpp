#include "core/geometry/triangle.h"

#include <cmath>
#include <limits>

namespace penumbra {
namespace {

constexpr float gammaN(int n) {
  constexpr float eps = std::numeric_limits<float>::epsilon() * 0.5f;
  return (n * eps) / (1.f - n * eps);
}

inline int maxDimension(const Vec3& v) {
  return v.x > v.y ? (v.x > v.z ? 0 : 2) : (v.y > v.z ? 1 : 2);
}
inline Vec3 permute(const Vec3& v, int x, int y, int z) {
  return Vec3(v[x], v[y], v[z]);
}

}  // namespace

bool intersectTriangle(const Ray& ray, float tMax, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                       TriangleIntersection& out) {
  // Translate to the ray origin, permute so the largest direction component is z, shear so d = +z.
  Vec3 p0t = p0 - ray.o, p1t = p1 - ray.o, p2t = p2 - ray.o;
  const int kz = maxDimension(glm::abs(ray.d));
  const int kx = kz == 2 ? 0 : kz + 1;
  const int ky = kx == 2 ? 0 : kx + 1;
  const Vec3 d = permute(ray.d, kx, ky, kz);
  p0t = permute(p0t, kx, ky, kz);
  p1t = permute(p1t, kx, ky, kz);
  p2t = permute(p2t, kx, ky, kz);
  const float sz = 1.f / d.z;
  const float sx = -d.x * sz;
  const float sy = -d.y * sz;
  p0t.x += sx * p0t.z;
  p0t.y += sy * p0t.z;
  p1t.x += sx * p1t.z;
  p1t.y += sy * p1t.z;
  p2t.x += sx * p2t.z;
  p2t.y += sy * p2t.z;

  // Edge functions; exact zeros (ray through an edge) are re-evaluated in double.
  float e0 = p1t.x * p2t.y - p1t.y * p2t.x;
  float e1 = p2t.x * p0t.y - p2t.y * p0t.x;
  float e2 = p0t.x * p1t.y - p0t.y * p1t.x;
  if (e0 == 0.f || e1 == 0.f || e2 == 0.f) {
    e0 = static_cast<float>(double(p1t.x) * p2t.y - double(p1t.y) * p2t.x);
    e1 = static_cast<float>(double(p2t.x) * p0t.y - double(p2t.y) * p0t.x);
    e2 = static_cast<float>(double(p0t.x) * p1t.y - double(p0t.y) * p1t.x);
  }
  if ((e0 < 0.f || e1 < 0.f || e2 < 0.f) && (e0 > 0.f || e1 > 0.f || e2 > 0.f)) return false;
  const float det = e0 + e1 + e2;
  if (det == 0.f) return false;

  p0t.z *= sz;
  p1t.z *= sz;
  p2t.z *= sz;
  const float tScaled = e0 * p0t.z + e1 * p1t.z + e2 * p2t.z;
  if (det < 0.f && (tScaled >= 0.f || tScaled < tMax * det)) return false;
  if (det > 0.f && (tScaled <= 0.f || tScaled > tMax * det)) return false;

  const float invDet = 1.f / det;
  const float t = tScaled * invDet;
  if (!(t < tMax) || !(t > ray.tMin)) return false;

  // Conservative check that t > 0 (pbrt-v4, 6.5.3): reject hits within the rounding error of t.
  const float maxZt = maxComponent(glm::abs(Vec3(p0t.z, p1t.z, p2t.z)));
  const float deltaZ = gammaN(3) * maxZt;
  const float maxXt = maxComponent(glm::abs(Vec3(p0t.x, p1t.x, p2t.x)));
  const float maxYt = maxComponent(glm::abs(Vec3(p0t.y, p1t.y, p2t.y)));
  const float deltaX = gammaN(5) * (maxXt + maxZt);
  const float deltaY = gammaN(5) * (maxYt + maxZt);
  const float deltaE = 2.f * (gammaN(2) * maxXt * maxYt + deltaY * maxXt + deltaX * maxYt);
  const float maxE = maxComponent(glm::abs(Vec3(e0, e1, e2)));
  const float deltaT = 3.f * (gammaN(3) * maxE * maxZt + deltaE * maxZt + deltaZ * maxE) * std::abs(invDet);
  if (t <= deltaT) return false;

  out.t = t;
  out.b0 = e0 * invDet;
  out.b1 = e1 * invDet;
  out.b2 = e2 * invDet;
  return true;
}

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
