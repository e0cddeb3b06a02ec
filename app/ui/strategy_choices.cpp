#include "app/ui/strategy_choices.h"

#include "core/analysis/strategy_lists.h"
#include "core/math/error.h"
#include "core/render/strategy_axes.h"
#include "core/scene/light_selection_default.h"

namespace penumbra::ui {

std::string strategyUnavailableReason(const IntegratorDesc& choice, const Scene* scene) {
  const bool areaLights = scene && scene->hasAreaLights();
  if (!strategyApplies(choice, areaLights))
    return std::string(sceneNeedText(sceneNeed(choice))) + " (renders " +
           strategyLabel(applicableStrategy(choice, false)) + " here)";
  const bool deltaLights = scene && scene->hasDeltaLights();
  // simple lights with point and directional lights only; hemisphere directions find area lights
  // by chance and add the point and directional ones: without any, both render black.
  if (choice.type == IntegratorType::Simple && !deltaLights) return "needs point or directional lights";
  const bool hemisphere = choice.type == IntegratorType::Direct && choice.estimator == Estimator::Hemisphere;
  if (hemisphere && !deltaLights && !areaLights) return "needs lights: the scene has none";
  return {};
}

std::string lightSelectionDefaultText(size_t areaLights) {
  return "default for " + areaLightsText(areaLights) + ": " +
         std::string(nameOf(defaultLightSelection(areaLights))) + " (" +
         std::string(nameOf(LightSelection::All)) + " up to " + std::to_string(kAllLightsUpTo) + ")";
}

bool offersCompare(const IntegratorDesc& left) {
  return everyStrategyOfType(left).size() > 1;
}

bool comparable(const IntegratorDesc& right, const IntegratorDesc& left, bool sceneHasAreaLights) {
  return offersCompare(left) && right.type == left.type && strategyApplies(right, sceneHasAreaLights);
}

IntegratorDesc defaultCompareStrategy(const IntegratorDesc& left, bool sceneHasAreaLights) {
  for (const IntegratorDesc& d : everyStrategyOfType(left))
    if (strategyApplies(d, sceneHasAreaLights) && !(d == left)) return d;
  return left;
}

IntegratorDesc parseCompareStrategy(const std::string& name, const IntegratorDesc& left,
                                    bool sceneHasAreaLights) {
  if (!offersCompare(left))
    throw Error("--compare " + name + ": the scene's " + strategyLabel(left) +
                " has no other strategy to compare with");
  try {
    const std::vector<IntegratorDesc> named = parseStrategies(left, name);
    if (named.size() == 1 && strategyApplies(named.front(), sceneHasAreaLights)) return named.front();
  } catch (const Error&) {
  }
  std::string accepted;
  for (std::string_view measure : measureChoices(left.type))
    if (strategyApplies(parseStrategies(left, std::string(measure)).front(), sceneHasAreaLights))
      (accepted += accepted.empty() ? "" : ", ") += measure;
  throw Error("--compare " + name + ": expected one " + std::string(nameOf(left.type)) +
              " strategy that applies to this scene: " + accepted);
}

}  // namespace penumbra::ui
