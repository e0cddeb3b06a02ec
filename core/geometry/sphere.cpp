#include "core/geometry/sphere.h"

#include <cmath>
#include <utility>

namespace penumbra {
void Sphere::fillHit(const Ray& ray, float t, uint32_t objectId, SurfaceHit& hit) const {
  const DVec3 c(center);
  DVec3 n = DVec3(ray.o) + static_cast<double>(t) * DVec3(ray.d) - c;
  const double len = glm::length(n);
  n = len > 0.0 ? n * (1.0 / len) : DVec3(0, 0, 1);
  const DVec3 p = c + static_cast<double>(radius) * n;
  hit.t = t;
  hit.p = Vec3(p);
  hit.ng = Vec3(n);
  hit.ns = hit.ng;
  hit.offsetScale = std::max(maxAbsComponent(hit.p), maxAbsComponent(center) + radius);
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
