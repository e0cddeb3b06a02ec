// A scene ready to render: geometry behind its queries, one material per object, and the lights.
// Built once per scene file; integrator, sampler and camera changes never touch it.
#pragma once

#include <cstdint>
#include <vector>

#include "core/geometry/scene_geometry.h"
#include "core/lights/directional_light.h"
#include "core/lights/light_bvh.h"
#include "core/lights/light_selection.h"
#include "core/lights/point_light.h"
#include "core/lights/sphere_light.h"
#include "core/math/vec.h"

namespace penumbra {

struct SurfaceMaterial {
  Color3 albedo{0.5f};       // diffuse reflectance
  int32_t sphereLight = -1;  // index into Scene::sphereLights when the object emits
};

struct Scene {
  SceneGeometry geometry;
  std::vector<SurfaceMaterial> materials;  // indexed by SurfaceHit::objectId
  std::vector<SphereLight> sphereLights;
  // Ways to choose one of sphereLights per shading sample (buildLightSelections fills them).
  UniformLightSelection uniformSelection;
  PowerLightSelection powerSelection;
  LightBvh lightBvh;
  std::vector<PointLight> pointLights;
  std::vector<DirectionalLight> directionalLights;
  // Longest segment inside the scene's bounds: AO rays and directional shadow rays stop there.
  float rayLengthBound = 0.f;

  bool hasAreaLights() const { return !sphereLights.empty(); }
  bool hasDeltaLights() const { return !pointLights.empty() || !directionalLights.empty(); }
};

// Builds the light selections over scene.sphereLights; call after the last light is added.
inline void buildLightSelections(Scene& scene) {
  scene.uniformSelection = makeUniformLightSelection(scene.sphereLights);
  scene.powerSelection = makePowerLightSelection(scene.sphereLights);
  scene.lightBvh = makeLightBvh(scene.sphereLights);
}

}  // namespace penumbra
