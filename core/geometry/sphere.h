// Analytic sphere: robust ray intersection (closest-approach discriminant, in double).
#pragma once

#include <cmath>
#include <cstdint>
#include <utility>

#include "core/geometry/bounds.h"
#include "core/geometry/ray.h"
#include "core/geometry/surface_hit.h"

namespace penumbra {

struct Sphere {
  Vec3 center{0.f};
  float radius = 1.f;

  // Nearest root t of |o + t·d − c| = r with ray.tMin < t < ray.tMax. Computed in double with the
  // closest-approach form of the discriminant (Ray Tracing Gems ch. 7, pbrt-v4), so a 1e-4 sphere at
  // 1e4 and a ray starting on the surface are both handled.
  bool intersect(const Ray& ray, float& tHit) const;
  // Any root in (tMin, tMax).
  bool occludes(const Ray& ray) const;
  // Fills hit data for a t returned by intersect: p is re-projected onto the sphere, c + r·normalize(p − c).
  void fillHit(const Ray& ray, float t, uint32_t objectId, SurfaceHit& hit) const;
  Bounds bounds() const;

  // Cheap float pre-test: false only if the ray's line certainly misses (closest approach beyond r by
  // far more than the float rounding of a·(|f|² − r²) − b², bounded by a few ulps of a·|f|²).
  // Inconclusive cases (tiny far spheres, near-silhouette rays, NaN) go to the double path.
  bool mayHit(const Ray& ray) const {
    const Vec3 f = ray.o - center;
    const float a = glm::dot(ray.d, ray.d), b = glm::dot(f, ray.d), ff = glm::dot(f, f);
    return !(a * (ff - radius * radius) - b * b > 1e-5f * a * ff);
  }

  // Both roots t0 <= t1 of the ray-sphere quadratic; false if the ray's line misses the sphere.
  bool roots(const Ray& ray, double& t0, double& t1) const {
    if (!mayHit(ray)) return false;
    const DVec3 f = DVec3(ray.o) - DVec3(center);
    const DVec3 d(ray.d);
    const double r = radius;
    const double a = glm::dot(d, d);
    const double invA = 1.0 / a;
    const double b = glm::dot(f, d);  // half of the usual b
    // Closest-approach form: b^2 - a·c = a·(r^2 - |f - (b/a)·d|^2), accurate when |f| >> r.
    const DVec3 v = f - (b * invA) * d;
    const double disc = r * r - glm::dot(v, v);
    if (!(disc >= 0.0)) return false;  // also rejects NaN (degenerate d)
    const double c = glm::dot(f, f) - r * r;
    const double q = -(b + std::copysign(std::sqrt(a * disc), b));
    t1 = q * invA;
    t0 = q != 0.0 ? c / q : t1;  // q == 0 only for r == 0 grazing the centre (then c == 0 too)
    if (t0 > t1) std::swap(t0, t1);
    return true;
  }
};

inline bool Sphere::intersect(const Ray& ray, float& tHit) const {
  double t0, t1;
  if (!roots(ray, t0, t1)) return false;
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

inline bool Sphere::occludes(const Ray& ray) const {
  double t0, t1;
  if (!roots(ray, t0, t1)) return false;
  return (t0 > ray.tMin && t0 < ray.tMax) || (t1 > ray.tMin && t1 < ray.tMax);
}

}  // namespace penumbra
