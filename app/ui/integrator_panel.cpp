#include <algorithm>
#include <string>

#include <imgui.h>

#include "app/ui/panel_text.h"
#include "app/ui/panels.h"
#include "core/render/light_selection_rows.h"

namespace penumbra::ui {

void drawIntegratorPanel(ViewerController& c, PanelState&) {
  if (!ImGui::CollapsingHeader("Integrator", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const bool areaLights = c.sceneHasAreaLights();

  // One entry per measure (its all-lights row), in table order; those the scene cannot use are
  // disabled. The light selection is the control below, so picking a measure keeps it.
  const Strategy live = c.settings().integrator.strategy;
  if (ImGui::BeginCombo("strategy", std::string(strategyRow(allLightsRow(live)).label).c_str())) {
    for (Strategy choice : c.strategyChoices()) {
      const StrategyRow& row = strategyRow(choice);
      bool applies = strategyApplies(choice, areaLights);
      if (ImGui::Selectable(std::string(row.label).c_str(), choice == allLightsRow(live),
                            applies ? 0 : ImGuiSelectableFlags_Disabled))
        c.setStrategy(choice);
      if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
        ImGui::SetTooltip("%s%s", std::string(row.description).c_str(),
                          applies ? "" : (std::string(" (") + sceneNeedText(row.needs) + ")").c_str());
    }
    ImGui::EndCombo();
  }
  // Which lights each shading sample samples: a row of the table each, switched live. Two rows
  // whatever the strategy, so the sections below never move.
  if (c.takesLightSelection()) {
    const Strategy now = c.settings().integrator.strategy;
    const LightSelection selected = lightSelectionOf(now);
    if (ImGui::BeginCombo("light selection", std::string(lightSelectionName(selected)).c_str())) {
      for (LightSelection l : lightSelectionsOf(now)) {
        std::string name(lightSelectionName(l));
        if (l == c.defaultLightSelection()) name += "  (default here)";
        if (ImGui::Selectable(name.c_str(), l == selected)) c.setLightSelection(l);
        if (ImGui::IsItemHovered())
          ImGui::SetTooltip("%s", std::string(strategyRow(*withLightSelection(now, l)).description).c_str());
      }
      ImGui::EndCombo();
    }
    hintText("%s", c.lightSelectionDefaultText().c_str());
  } else {
    ImGui::TextDisabled("(no light selection)");
    ImGui::TextUnformatted("");
  }

  RenderSettings s = c.settings();
  IntegratorDesc& d = s.integrator;
  // Fixed height: the fallback line and the strategy's settings keep their rows whatever the
  // strategy, so the sections below never move when it changes.
  Strategy rendered = applicableStrategy(d.strategy, areaLights);
  if (rendered == d.strategy) ImGui::TextUnformatted("");
  if (rendered != d.strategy) {
    hintText("%s %s: %s", std::string(strategyRow(d.strategy).label).c_str(),
             sceneNeedText(strategyRow(d.strategy).needs), std::string(strategyRow(rendered).label).c_str());
    d.strategy = rendered;
  }
  const StrategyRow& row = strategyRow(d.strategy);
  const Spellings& samples = row.samplesProperty;
  // The same number of rows for every strategy: the mis rows' counts and heuristic instead of the
  // shading samples; blank rows below the others.
  int settingRows = 0;
  const bool hasCounts = !row.counts[0].name.empty();
  if (hasCounts) {
    for (const CountProperty& count : row.counts) {
      if (count.name.empty()) continue;
      int n = d.*count.field;
      if (ImGui::InputInt(std::string(count.name.canonical()).c_str(), &n, 1, 8,
                          ImGuiInputTextFlags_EnterReturnsTrue) ||
          ImGui::IsItemDeactivatedAfterEdit())
        d.*count.field = std::clamp(n, 1, 1 << 16);
      ++settingRows;
    }
    for (const StrategyProperty& p : row.select)
      if (p.name.canonical() == "heuristic") {
        ImGui::Text("heuristic: %s", std::string(p.value.canonical()).c_str());
        ++settingRows;
      }
  } else if (!samples.empty()) {
    int n = d.samples;
    if (ImGui::InputInt(std::string(samples.canonical()).c_str(), &n, 1, 8,
                        ImGuiInputTextFlags_EnterReturnsTrue) ||
        ImGui::IsItemDeactivatedAfterEdit())
      d.samples = std::clamp(n, 1, 1 << 16);
    ++settingRows;
  } else {
    ImGui::TextDisabled("(no shading samples)");
    ++settingRows;
  }
  for (; settingRows < int(kMaxCounts) + 1; ++settingRows) ImGui::TextUnformatted("");
  c.setSettings(s);  // restarts only if something changed

  // Compare mode: a second strategy right of a draggable divider, equal shares of time.
  ImGui::Separator();
  ImGui::TextUnformatted("Compare");
  if (c.compareChoices().empty()) {  // e.g. simple, normals: nothing to compare with
    hintText("%s has no sampling strategies to compare", strategyLabel(c.settings().integrator).c_str());
    if (c.compareEnabled()) c.setCompare(false);
    ImGui::TextUnformatted("");  // the rows the checkbox and combo take otherwise
    return;
  }
  bool on = c.compareEnabled();
  if (ImGui::Checkbox("split view", &on)) c.setCompare(on);
  IntegratorDesc r = c.compareIntegrator();
  // The controller's choices: the left side's integrator type, with shading samples, applicable to
  // the scene; the combo shows exactly what the right side renders.
  if (ImGui::BeginCombo("right side", strategyLabel(c.renderedCompareIntegrator()).c_str())) {
    for (Strategy s : c.compareChoices()) {
      const StrategyRow& row = strategyRow(s);
      if (ImGui::Selectable(std::string(row.label).c_str(), row.strategy == r.strategy))
        c.setCompareIntegrator(IntegratorDesc{row.strategy, r.samples});
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", std::string(row.description).c_str());
    }
    ImGui::EndCombo();
  }
  if (c.compareEnabled()) {
    float pct = c.display.compareDivider * 100.f;
    if (ImGui::SliderFloat("divider", &pct, 0.f, 100.f, "%.0f %%")) c.display.compareDivider = pct / 100.f;
    hintText("%d thread(s) per side, equal time; drag the line in the image", c.engineThreads());
  }
}

}  // namespace penumbra::ui
