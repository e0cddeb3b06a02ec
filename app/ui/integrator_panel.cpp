#include <algorithm>
#include <string>

#include <imgui.h>

#include "app/ui/panels.h"

namespace penumbra::ui {

void drawIntegratorPanel(ViewerController& c, PanelState&) {
  if (!ImGui::CollapsingHeader("Integrator", ImGuiTreeNodeFlags_DefaultOpen)) return;
  RenderSettings s = c.settings();
  IntegratorDesc& d = s.integrator;
  const bool areaLights = c.sceneHasAreaLights();

  // Every strategy of the table, in its order; those the scene cannot use are disabled.
  if (ImGui::BeginCombo("strategy", std::string(strategyRow(d.strategy).label).c_str())) {
    for (const StrategyRow& row : strategyTable()) {
      bool applies = strategyApplies(row.strategy, areaLights);
      if (ImGui::Selectable(std::string(row.label).c_str(), row.strategy == d.strategy,
                            applies ? 0 : ImGuiSelectableFlags_Disabled))
        d.strategy = row.strategy;
      if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
        ImGui::SetTooltip("%s%s", std::string(row.description).c_str(),
                          applies ? "" : (std::string(" (") + sceneNeedText(row.needs) + ")").c_str());
    }
    ImGui::EndCombo();
  }
  Strategy rendered = applicableStrategy(d.strategy, areaLights);
  if (rendered != d.strategy) {
    ImGui::TextDisabled("%s %s: %s", std::string(strategyRow(d.strategy).label).c_str(),
                        sceneNeedText(strategyRow(d.strategy).needs),
                        std::string(strategyRow(rendered).label).c_str());
    d.strategy = rendered;
  }
  const Spellings& samples = strategyRow(d.strategy).samplesProperty;
  if (!samples.empty()) {
    int n = d.samples;
    if (ImGui::InputInt(std::string(samples.canonical()).c_str(), &n, 1, 8,
                        ImGuiInputTextFlags_EnterReturnsTrue) ||
        ImGui::IsItemDeactivatedAfterEdit())
      d.samples = std::clamp(n, 1, 1 << 16);
  }
  c.setSettings(s);  // restarts only if something changed

  // Compare mode: a second strategy right of a draggable divider, equal shares of time.
  ImGui::Separator();
  ImGui::TextUnformatted("Compare");
  bool on = c.compareEnabled();
  if (ImGui::Checkbox("split view", &on)) c.setCompare(on);
  IntegratorDesc r = c.compareIntegrator();
  // The strategies with shading samples (the Monte Carlo estimators), with the same scene, camera and
  // sampler as the left side.
  if (ImGui::BeginCombo("right side", strategyLabel(r).c_str())) {
    for (const StrategyRow& row : strategyTable()) {
      if (row.samplesProperty.empty() || !strategyApplies(row.strategy, areaLights)) continue;
      if (ImGui::Selectable(std::string(row.label).c_str(), row.strategy == r.strategy))
        c.setCompareIntegrator(IntegratorDesc{row.strategy, r.samples});
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", std::string(row.description).c_str());
    }
    ImGui::EndCombo();
  }
  if (c.compareEnabled()) {
    float pct = c.display.compareDivider * 100.f;
    if (ImGui::SliderFloat("divider", &pct, 0.f, 100.f, "%.0f %%")) c.display.compareDivider = pct / 100.f;
    ImGui::TextDisabled("%d thread(s) per side; drag the line in the image", c.engineThreads());
  }
}

}  // namespace penumbra::ui
