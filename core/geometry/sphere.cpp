#include "core/geometry/sphere.h"

#include <cmath>
#include <utility>

namespace penumbra {
namespace {

// Both roots t0 <= t1 of the ray-sphere quadratic; false if the ray misses the sphere.
inline bool sphereRoots(const Sphere& s, const Ray& ray, double& t0, double& t1) {
  const DVec3 f = DVec3(ray.o) - DVec3(s.center);
  const DVec3 d(ray.d);
  const double r = s.radius;
  const double a = glm::dot(d, d);
  const double b = glm::dot(f, d);  // half of the usual b
  // Closest-approach form: b^2 - a·c = a·(r^2 - |f - (b/a)·d|^2), accurate when |f| >> r.
  const DVec3 v = f - (b / a) * d;
  const double disc = r * r - glm::dot(v, v);
  if (!(disc >= 0.0)) return false;  // also rejects NaN (degenerate d)
  const double c = glm::dot(f, f) - r * r;
  const double q = -(b + std::copysign(std::sqrt(a * disc), b));
  t0 = c / q;
  t1 = q / a;
  if (q == 0.0) t0 = t1;  // r == 0 tangent case: c == 0 too
  if (t0 > t1) std::swap(t0, t1);
  return true;
}

}  // namespace

bool Sphere::intersect(const Ray& ray, float& tHit) const {
  double t0, t1;
  if (!sphereRoots(*this, ray, t0, t1)) return false;
  double t;
  if (t0 > ray.tMin && t0 < ray.tMax)
    t = t0;
  else if (t1 > ray.tMin && t1 < ray.tMax)
    t = t1;
  else
    return false;
  tHit = static_cast<float>(t);
  return true;
}

bool Sphere::occludes(const Ray& ray) const {
  double t0, t1;
  if (!sphereRoots(*this, ray, t0, t1)) return false;
  return (t0 > ray.tMin && t0 < ray.tMax) || (t1 > ray.tMin && t1 < ray.tMax);
}

void Sphere::fillHit(const Ray& ray, float t, uint32_t objectId, SurfaceHit& hit) const {
  const DVec3 c(center);
  DVec3 n = DVec3(ray.o) + static_cast<double>(t) * DVec3(ray.d) - c;
  const double len = glm::length(n);
  n = len > 0.0 ? n / len : DVec3(0, 0, 1);
  const DVec3 p = c + static_cast<double>(radius) * n;
  hit.t = t;
  hit.p = Vec3(p);
  hit.ng = Vec3(n);
  hit.ns = hit.ng;
  hit.offsetScale = std::max(maxComponent(glm::abs(hit.p)), maxComponent(glm::abs(center)) + radius);
  hit.objectId = objectId;
  hit.primId = 0;
}

Bounds Sphere::bounds() const {
  Bounds b;
  b.expand(center - Vec3(radius));
  b.expand(center + Vec3(radius));
  return b;
}

}  // namespace penumbra
