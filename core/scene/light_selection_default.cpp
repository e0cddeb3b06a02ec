#include "core/scene/light_selection_default.h"

#include "core/render/light_selection_rows.h"

namespace penumbra {

size_t countSphereLights(const SceneNode& scene) {
  size_t n = 0;
  for (const SceneNode& c : scene.children)
    if (c.tag == "shape" && c.type == "sphere" && c.child("emitter")) ++n;
  return n;
}

std::string sphereLightsText(size_t count) {
  return std::to_string(count) + (count == 1 ? " sphere light" : " sphere lights");
}

bool sceneNamesLightSelection(const SceneNode& scene) {
  const SceneNode* integrator = scene.child("integrator");
  return integrator && integrator->props.find(lightSelectionProperty().list()) != nullptr;
}

std::string lightSelectionSummary(const SceneNode& scene, Strategy strategy) {
  if (!takesLightSelection(strategy)) return "";
  std::string out = "light selection " + std::string(lightSelectionName(lightSelectionOf(strategy)));
  if (sceneNamesLightSelection(scene)) return out + " (named by the scene or --set)";
  return out + " (the default for " + sphereLightsText(countSphereLights(scene)) + ": " +
         std::string(lightSelectionName(LightSelection::All)) + " up to " + std::to_string(kAllLightsUpTo) +
         ", " + std::string(lightSelectionName(kManyLightsSelection)) + " above)";
}

}  // namespace penumbra
