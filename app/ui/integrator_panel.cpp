#include <algorithm>
#include <string>

#include <imgui.h>

#include "app/ui/number_input.h"
#include "app/ui/panel_text.h"
#include "app/ui/panels.h"
#include "core/render/light_selection_rows.h"

namespace penumbra::ui {

namespace {

// The line under the light selection for `s` (named in the combo above): why it renders another
// strategy, or why it cannot light this scene ("" when neither).
std::string strategyNote(const ViewerController& c, Strategy s) {
  const Strategy rendered = applicableStrategy(s, c.sceneHasAreaLights());
  if (rendered != s)
    return std::string(sceneNeedText(strategyRow(s).needs)) + ": renders " +
           std::string(strategyRow(rendered).label);
  return c.strategyUnavailableReason(s);
}

}  // namespace

void drawIntegratorPanel(ViewerController& c, PanelState&) {
  if (!ImGui::CollapsingHeader("Integrator", ImGuiTreeNodeFlags_DefaultOpen)) return;

  // One entry per measure (its all-lights row), in table order; those that cannot light the scene
  // are greyed out. The light selection is the control below, so picking a measure keeps it.
  const Strategy live = c.settings().integrator.strategy;
  if (ImGui::BeginCombo("strategy", std::string(strategyRow(allLightsRow(live)).label).c_str())) {
    for (Strategy choice : c.strategyChoices()) {
      const StrategyRow& row = strategyRow(choice);
      // Greyed out, with the reason, where the strategy cannot light this scene.
      const std::string reason = c.strategyUnavailableReason(choice);
      std::string label(row.label);
      if (!reason.empty()) label += "  (cannot light this scene)";
      if (ImGui::Selectable(label.c_str(), choice == allLightsRow(live),
                            reason.empty() ? 0 : ImGuiSelectableFlags_Disabled))
        c.setStrategy(choice);
      if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
        ImGui::SetTooltip("%s%s", std::string(row.description).c_str(),
                          reason.empty() ? "" : ("\n" + reason).c_str());
    }
    ImGui::EndCombo();
  }

  // Every block below keeps one height whatever the strategy, so the sections below never move
  // when it changes.
  // Which lights each shading sample samples: a row of the table each, switched live; the line
  // under it says the scene's default (a text that depends on the scene only).
  const std::string defaultText = c.lightSelectionDefaultText();
  float top = ImGui::GetCursorPosY();
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
    hintText("%s", defaultText.c_str());
  } else {
    ImGui::AlignTextToFramePadding();
    ImGui::TextDisabled("(no light selection)");
  }
  padBlockTo(top, frameRowHeight() + textBlockHeight(defaultText.c_str()));

  RenderSettings s = c.settings();
  IntegratorDesc& d = s.integrator;
  // The note on the strategy (what renders instead, or why it cannot light the scene): as tall as
  // the tallest note any strategy has on this scene.
  float noteHeight = textBlockHeight(" ");
  for (const StrategyRow& row : strategyTable())
    noteHeight = std::max(noteHeight, textBlockHeight(strategyNote(c, row.strategy).c_str()));
  top = ImGui::GetCursorPosY();
  const std::string note = strategyNote(c, d.strategy);
  if (!note.empty()) hintText("%s", note.c_str());
  padBlockTo(top, noteHeight);
  d.strategy = applicableStrategy(d.strategy, c.sceneHasAreaLights());

  // The strategy's settings, one row each: the mis rows' counts and heuristic, or the shading
  // samples; as many rows as the strategy with the most.
  const StrategyRow& row = strategyRow(d.strategy);
  const Spellings& samples = row.samplesProperty;
  top = ImGui::GetCursorPosY();
  if (!row.counts[0].name.empty()) {
    for (const CountProperty& count : row.counts) {
      if (count.name.empty()) continue;
      const std::string name(count.name.canonical());
      if (auto n = numberInput(name.c_str(), shadingSamplesField(name), d.*count.field, 1, 8))
        d.*count.field = int(*n);
    }
    for (const StrategyProperty& p : row.select)
      if (p.name.canonical() == "heuristic") {
        ImGui::AlignTextToFramePadding();
        ImGui::Text("heuristic: %s", std::string(p.value.canonical()).c_str());
      }
  } else if (!samples.empty()) {
    const std::string name(samples.canonical());
    if (auto n = numberInput(name.c_str(), shadingSamplesField(name), d.samples, 1, 8)) d.samples = int(*n);
  } else {
    ImGui::AlignTextToFramePadding();
    ImGui::TextDisabled("(no shading samples)");
  }
  padBlockTo(top, float(kMaxCounts + 1) * frameRowHeight());
  c.setSettings(s);  // restarts only if something changed

  // Compare mode: a second strategy right of a draggable divider, equal shares of time.
  ImGui::Separator();
  ImGui::TextUnformatted("Compare");
  top = ImGui::GetCursorPosY();
  if (c.compareChoices().empty()) {  // e.g. simple, normals: nothing to compare with
    hintText("%s has no sampling strategies to compare", strategyLabel(c.settings().integrator).c_str());
    if (c.compareEnabled()) c.setCompare(false);
    padBlockTo(top, 2.f * frameRowHeight());  // the rows the checkbox and combo take otherwise
    return;
  }
  bool on = c.compareEnabled();
  if (ImGui::Checkbox("split view", &on)) c.setCompare(on);
  IntegratorDesc r = c.compareIntegrator();
  // The controller's choices: the left side's integrator type, with shading samples, applicable to
  // the scene; the combo shows exactly what the right side renders.
  if (ImGui::BeginCombo("right side", strategyLabel(c.renderedCompareIntegrator()).c_str())) {
    for (Strategy choice : c.compareChoices()) {
      const StrategyRow& choiceRow = strategyRow(choice);
      if (ImGui::Selectable(std::string(choiceRow.label).c_str(), choiceRow.strategy == r.strategy))
        c.setCompareIntegrator(IntegratorDesc{choiceRow.strategy, r.samples});
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", std::string(choiceRow.description).c_str());
    }
    ImGui::EndCombo();
  }
  if (c.compareEnabled()) {
    float pct = c.display.compareDivider * 100.f;
    if (numberSlider("divider", fields::kDividerPercent, pct, 0.f, 100.f, "%.0f %%"))
      c.display.compareDivider = pct / 100.f;
    hintText("%d thread(s) per side, equal time; drag the line in the image", c.engineThreads());
  }
}

}  // namespace penumbra::ui
