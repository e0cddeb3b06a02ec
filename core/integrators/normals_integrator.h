// "normals": the absolute shading normal as a colour; black where the camera ray misses.
#pragma once

#include <glm/common.hpp>

#include "core/sampling/sampler.h"
#include "core/world/scene.h"

namespace penumbra {

struct NormalsIntegrator {
  Color3 Li(const Scene& scene, const Ray& ray, Sampler&) const {
    SurfaceHit hit;
    if (!scene.geometry.intersect(ray, hit)) return Color3(0.f);
    return glm::abs(hit.ns);
  }
};

}  // namespace penumbra
