#include "core/scene/light_selection_default.h"

#include "core/render/strategy_axes.h"

namespace penumbra {

size_t countSphereLights(const SceneNode& scene) {
  size_t n = 0;
  for (const SceneNode& c : scene.children)
    if (c.tag == "shape" && c.type == "sphere" && c.child("emitter")) ++n;
  return n;
}

std::string areaLightsText(size_t count) {
  return std::to_string(count) + (count == 1 ? " area light" : " area lights");
}

bool sceneNamesLightSelection(const SceneNode& scene) {
  const SceneNode* integrator = scene.child("integrator");
  return integrator && integrator->props.find(kLightSelectionProperty.list()) != nullptr;
}

std::string lightSelectionSummary(const SceneNode& scene, const IntegratorDesc& strategy, size_t areaLights) {
  if (!strategy.usesLightSelection()) return "";
  std::string out = "light selection " + std::string(nameOf(strategy.lightSelection));
  if (sceneNamesLightSelection(scene)) return out + " (named by the scene or --set)";
  return out + " (the default for " + areaLightsText(areaLights) + ": " +
         std::string(nameOf(LightSelection::All)) + " up to " + std::to_string(kAllLightsUpTo) + ", " +
         std::string(nameOf(kManyLightsSelection)) + " above)";
}

}  // namespace penumbra
