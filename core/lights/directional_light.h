// Distant light. `direction` points FROM the scene TOWARD the light (scenes/hw1's
// sphere-directional.xml: direction = (1, 1, 0) lights a plane at y = −0.05 from above), so the light
// travels along −direction. `irradiance` is the scene XML's "radiance" property: the irradiance on a
// surface facing the light, E = irradiance · max(0, dot(n, direction)) · V.
#pragma once

#include <cmath>

#include "core/lights/point_light.h"

namespace penumbra {

struct DirectionalLight {
  Vec3 direction{0.f, 0.f, 1.f};  // unit, toward the light; use make() to normalise user input
  Color3 irradiance{0.f};

  static DirectionalLight make(const Vec3& towardLight, const Color3& irradiance) {
    const float len = glm::length(towardLight);
    return DirectionalLight{len > 0.f ? towardLight / len : Vec3(0.f, 0.f, 1.f), irradiance};
  }

  DeltaLightSample sample(const Vec3& /*x*/) const {
    DeltaLightSample s;
    s.wi = direction;
    s.dist = INFINITY;
    s.Li = irradiance;
    return s;
  }
};

}  // namespace penumbra
