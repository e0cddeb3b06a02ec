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
#include "core/lights/polygon_light.h"
#include "core/lights/sphere_light.h"
#include "core/materials/bsdf.h"
#include "core/math/vec.h"

namespace penumbra {

struct SurfaceMaterial {
  Bsdf bsdf;                 // how the surface reflects (diffuse albedo 0.5 unless the scene says)
  int32_t sphereLight = -1;  // index into Scene::sphereLights when the object is an emitting sphere
  // When the object is an emitting mesh: where its triangles start in Scene::polygonLightOfPrim.
  int32_t polygonLightsAt = -1;

  bool emits() const { return sphereLight >= 0 || polygonLightsAt >= 0; }
};

struct Scene {
  SceneGeometry geometry;
  std::vector<SurfaceMaterial> materials;  // indexed by SurfaceHit::objectId
  std::vector<SphereLight> sphereLights;
  std::vector<PolygonLight> polygonLights;
  // Per triangle of each emitting mesh (from its material's polygonLightsAt), the index of the polygon
  // light it belongs to, or -1 for a degenerate triangle, which emits nothing.
  std::vector<int32_t> polygonLightOfPrim;
  // Ways to choose one area light per shading sample (buildLightSelections fills them). They index
  // the sphere lights first, then the polygon lights.
  UniformLightSelection uniformSelection;
  PowerLightSelection powerSelection;
  LightBvh lightBvh;
  std::vector<PointLight> pointLights;
  std::vector<DirectionalLight> directionalLights;
  // Longest segment inside the scene's bounds: AO rays and directional shadow rays stop there.
  float rayLengthBound = 0.f;

  bool hasAreaLights() const { return !sphereLights.empty() || !polygonLights.empty(); }
  bool hasGlossySurfaces() const {
    for (const SurfaceMaterial& m : materials)
      if (m.bsdf.reflects() && !m.bsdf.isDiffuse()) return true;
    return false;
  }
  size_t areaLightCount() const { return sphereLights.size() + polygonLights.size(); }
  // The polygon light that triangle `primId` of object `material` belongs to (null: it emits nothing).
  const PolygonLight* polygonLightOf(const SurfaceMaterial& material, uint32_t primId) const {
    if (material.polygonLightsAt < 0) return nullptr;
    const int32_t light = polygonLightOfPrim[size_t(material.polygonLightsAt) + primId];
    return light < 0 ? nullptr : &polygonLights[size_t(light)];
  }
  bool hasDeltaLights() const { return !pointLights.empty() || !directionalLights.empty(); }
};

// Builds the light selections over the sphere lights, then the polygon lights; call after the last
// light is added.
inline void buildLightSelections(Scene& scene) {
  std::vector<LightSummary> lights = summarizeLights(scene.sphereLights);
  for (const PolygonLight& l : scene.polygonLights) lights.push_back(summarizeLight(l));
  scene.uniformSelection = makeUniformLightSelection(lights);
  scene.powerSelection = makePowerLightSelection(lights);
  scene.lightBvh = makeLightBvh(lights);
}

}  // namespace penumbra
