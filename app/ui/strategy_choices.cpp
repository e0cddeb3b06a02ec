#include "app/ui/strategy_choices.h"

#include "core/math/error.h"
#include "core/render/light_selection_rows.h"
#include "core/render/strategy_table.h"
#include "core/scene/light_selection_default.h"

namespace penumbra::ui {

std::vector<Strategy> strategyChoices() {
  std::vector<Strategy> out;
  for (const StrategyRow& row : strategyTable())
    if (allLightsRow(row.strategy) == row.strategy) out.push_back(row.strategy);
  return out;
}

Strategy strategyForChoice(Strategy choice, Strategy live, LightSelection sceneDefault) {
  const LightSelection keep = penumbra::takesLightSelection(live) ? lightSelectionOf(live) : sceneDefault;
  return withLightSelection(choice, keep).value_or(choice);
}

std::string strategyUnavailableReason(Strategy choice, const Scene* scene) {
  const bool areaLights = scene && scene->hasAreaLights();
  const StrategyRow& row = strategyRow(choice);
  if (!strategyApplies(choice, areaLights))
    return std::string(sceneNeedText(row.needs)) + " (renders " +
           std::string(strategyRow(applicableStrategy(choice, false)).label) + " here)";
  const bool deltaLights = scene && scene->hasDeltaLights();
  // simple lights with point and directional lights only; the hemisphere strategies find area
  // lights by chance and add the point and directional ones: without any, both render black.
  if (choice == Strategy::Simple && !deltaLights) return "needs point or directional lights";
  const bool hemisphere =
      choice == Strategy::DirectUniformHemisphere || choice == Strategy::DirectCosineHemisphere;
  if (hemisphere && !deltaLights && !areaLights) return "needs lights: the scene has none";
  return {};
}

std::string lightSelectionDefaultText(size_t sphereLights) {
  return "default for " + sphereLightsText(sphereLights) + ": " +
         std::string(lightSelectionName(defaultLightSelection(sphereLights))) + " (" +
         std::string(lightSelectionName(LightSelection::All)) + " up to " + std::to_string(kAllLightsUpTo) +
         ")";
}

std::vector<Strategy> compareChoices(Strategy left, bool sceneHasAreaLights) {
  std::vector<Strategy> out;
  for (const StrategyRow& row : strategyTable())
    if (!row.samplesProperty.empty() && sameIntegratorType(row.strategy, left) &&
        strategyApplies(row.strategy, sceneHasAreaLights))
      out.push_back(row.strategy);
  return out;
}

IntegratorDesc parseCompareStrategy(const std::string& name, const IntegratorDesc& left,
                                    bool sceneHasAreaLights) {
  std::vector<Strategy> choices = compareChoices(left.strategy, sceneHasAreaLights);
  std::string names;
  for (Strategy s : choices) {
    const StrategyRow& row = strategyRow(s);
    if (name == row.shortName || name == row.label) return IntegratorDesc{s, left.samples};
    names += (names.empty() ? "" : ", ") + std::string(row.shortName);
  }
  if (choices.empty())
    throw Error("--compare " + name + ": the scene's " + strategyLabel(left) +
                " has no other strategy to compare with");
  throw Error("--compare " + name + ": expected one strategy that applies to this scene: " + names);
}

}  // namespace penumbra::ui
