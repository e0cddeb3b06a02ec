// Which lights `direct` samples when the scene leaves lightSelection out: every light for every
// shading sample while there are few, one chosen light per sample above a measured light count.
// The scene builder resolves the absent property with it; `render` and the viewer say what it chose.
#pragma once

#include <cstddef>
#include <string>

#include "core/integrators/integrator_desc.h"
#include "core/scene/scene_desc.h"

namespace penumbra {

// Measured crossover of equal-time efficiency (docs/estimators.md, "Many lights": the crossover table).
inline constexpr size_t kAllLightsUpTo = 256;
// The selection that wins above kAllLightsUpTo at every light count measured.
inline constexpr LightSelection kManyLightsSelection = LightSelection::Bvh;

// all up to kAllLightsUpTo area lights (spheres and polygons alike), kManyLightsSelection above.
constexpr LightSelection defaultLightSelection(size_t areaLights) {
  return areaLights <= kAllLightsUpTo ? LightSelection::All : kManyLightsSelection;
}

// The sphere lights a scene description builds (spheres with an area emitter).
size_t countSphereLights(const SceneNode& scene);
// "1 area light", "64 area lights".
std::string areaLightsText(size_t count);
// Whether the scene's <integrator> names its light selection.
bool sceneNamesLightSelection(const SceneNode& scene);

// What `render` prints (and writes into the image metadata) about the light selection of `strategy`
// in `scene` (with `areaLights` area lights once built): "" when the strategy takes none, else e.g.
// "light selection bvh (the default for 300 area lights: all up to 256, bvh above)" or "light selection
// power (named by the scene or --set)".
std::string lightSelectionSummary(const SceneNode& scene, const IntegratorDesc& strategy, size_t areaLights);

}  // namespace penumbra
