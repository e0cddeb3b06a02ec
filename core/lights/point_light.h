// Isotropic point light. `intensity` is the scene XML's "radiance" property of a point emitter
// (radiant intensity, W/sr): the irradiance it gives a surface is I · max(0, cos θ) / d² · V.
#pragma once

#include <cmath>

#include "core/lights/light_sample.h"

namespace penumbra {

struct PointLight {
  Vec3 position{0.f};
  Color3 intensity{0.f};

  // Li = I / d². x at the light's position gives Li = 0 (no direction).
  DeltaLightSample sample(const Vec3& x) const {
    DeltaLightSample s;
    const Vec3 toL = position - x;
    const float d2 = glm::dot(toL, toL);
    if (!(d2 > 0.f) || !std::isfinite(d2)) return s;
    s.dist = std::sqrt(d2);
    s.wi = toL / s.dist;
    s.Li = intensity / d2;
    return s;
  }
};

}  // namespace penumbra
