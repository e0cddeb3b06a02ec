// Analytic sphere: robust ray intersection (closest-approach discriminant, in double).
#pragma once

#include <cstdint>

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
};

}  // namespace penumbra
