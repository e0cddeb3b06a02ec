// The Integrator panel: one control per strategy axis, shown only where the axis applies (the
// integrator type, direct's measure, then the hemisphere warp, the light selection, or MIS's light
// measure and heuristic), the counts, and compare mode's right side with the same axis controls.
// Every block keeps one height whatever the strategy, so the sections below never move.
#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include <imgui.h>

#include "app/ui/number_input.h"
#include "app/ui/panel_text.h"
#include "app/ui/panels.h"

namespace penumbra::ui {

namespace {

// One entry of an axis combo.
struct AxisChoice {
  std::string name;         // shown
  std::string description;  // tooltip
  std::string unavailable;  // why it cannot light this scene: greyed out; "" when it can
  bool selected = false;
};

// A combo of `choices`; the index picked this frame, or -1.
int axisCombo(const char* label, const std::vector<AxisChoice>& choices) {
  int picked = -1;
  std::string preview;
  for (const AxisChoice& ch : choices)
    if (ch.selected) preview = ch.name;
  if (ImGui::BeginCombo(label, preview.c_str())) {
    for (size_t i = 0; i < choices.size(); ++i) {
      const AxisChoice& ch = choices[i];
      std::string text = ch.name;
      if (!ch.unavailable.empty()) text += "  (cannot light this scene)";
      ImGui::PushID(int(i));
      if (ImGui::Selectable(text.c_str(), ch.selected,
                            ch.unavailable.empty() ? 0 : ImGuiSelectableFlags_Disabled))
        picked = int(i);
      ImGui::PopID();
      if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
        ImGui::SetTooltip("%s%s", ch.description.c_str(),
                          ch.unavailable.empty() ? "" : ("\n" + ch.unavailable).c_str());
    }
    ImGui::EndCombo();
  }
  return picked;
}

// A combo over one axis table: each row's canonical name and description; `set` applies a row's
// value to a copy of d, `reason` says why that copy cannot light the scene.
template <class Row, size_t N, class Value>
void tableCombo(const char* label, const std::array<Row, N>& table, Value Row::*field,
                Spellings Row::*spellings, IntegratorDesc& d, Value IntegratorDesc::*axis,
                const std::function<std::string(const IntegratorDesc&)>& reason,
                const std::function<std::string(Value)>& suffix = {}) {
  std::vector<AxisChoice> choices;
  for (const Row& r : table) {
    IntegratorDesc candidate = d;
    candidate.*axis = r.*field;
    std::string name((r.*spellings).canonical());
    if (suffix) name += suffix(r.*field);
    choices.push_back({name, std::string(r.description), reason(candidate), d.*axis == r.*field});
  }
  if (int i = axisCombo(label, choices); i >= 0) d.*axis = table[size_t(i)].*field;
}

// direct's measure: hemisphere, each light measure, mis (measureNames order).
void measureCombo(const char* label, IntegratorDesc& d,
                  const std::function<std::string(const IntegratorDesc&)>& reason) {
  std::vector<AxisChoice> choices;
  const std::vector<std::string_view> names = measureNames();
  for (std::string_view name : names) {
    IntegratorDesc candidate = d;
    applyMeasure(name, candidate);
    const std::string_view description = candidate.estimator == Estimator::Light
                                             ? rowOf(candidate.lightMeasure).description
                                             : rowOf(candidate.estimator).description;
    choices.push_back(
        {std::string(name), std::string(description), reason(candidate), measureName(d) == name});
  }
  if (int i = axisCombo(label, choices); i >= 0) applyMeasure(names[size_t(i)], d);
}

// The axes below the measure: the warp, the light selection (with the scene's default under it),
// or MIS's light measure and heuristic; `id` tells the two sides' widgets apart. As tall as the
// tallest of them.
void axisBlock(ViewerController& c, IntegratorDesc& d, const char* id, bool withDefaultText) {
  const std::function<std::string(const IntegratorDesc&)> reason = [&](const IntegratorDesc& x) {
    return c.strategyUnavailableReason(x);
  };
  const auto label = [&](const char* name) { return std::string(name) + id; };
  const std::string defaultText = c.lightSelectionDefaultText();
  const float top = ImGui::GetCursorPosY();
  if (d.usesWarp()) {
    tableCombo(label("warp").c_str(), kWarps, &WarpRow::warp, &WarpRow::spellings, d, &IntegratorDesc::warp,
               reason);
  } else if (d.usesLightSelection()) {
    const LightSelection sceneDefault = c.defaultLightSelection();
    const std::function<std::string(LightSelection)> suffix = [&](LightSelection l) {
      return std::string(l == sceneDefault ? "  (default here)" : "");
    };
    tableCombo(label("light selection").c_str(), kLightSelections, &LightSelectionRow::selection,
               &LightSelectionRow::spellings, d, &IntegratorDesc::lightSelection, reason, suffix);
    if (withDefaultText) hintText("%s", defaultText.c_str());
  } else if (d.usesMisAxes()) {
    tableCombo(label("light measure").c_str(), kLightMeasures, &LightMeasureRow::measure,
               &LightMeasureRow::spellings, d, &IntegratorDesc::lightMeasure, reason);
    tableCombo(label("heuristic").c_str(), kHeuristics, &HeuristicRow::heuristic, &HeuristicRow::spellings, d,
               &IntegratorDesc::heuristic, reason);
  } else {
    ImGui::AlignTextToFramePadding();
    ImGui::TextDisabled("(no sampling axes)");
  }
  padBlockTo(top,
             std::max(2.f * frameRowHeight(),
                      frameRowHeight() + (withDefaultText ? textBlockHeight(defaultText.c_str()) : 0.f)));
}

// The line under the axes for `s`: why it renders another strategy, or why it cannot light this
// scene ("" when neither).
std::string strategyNote(const ViewerController& c, const IntegratorDesc& s) {
  const IntegratorDesc rendered = applicableStrategy(s, c.sceneHasAreaLights());
  if (!(rendered == s))
    return std::string(sceneNeedText(sceneNeed(s))) + ": renders " + strategyLabel(rendered);
  return c.strategyUnavailableReason(s);
}

// The counts, one row each: MIS's two, or the shading samples; two rows and a note's line whatever
// the strategy.
void countsBlock(IntegratorDesc& d) {
  const float top = ImGui::GetCursorPosY();
  const auto count = [&](const Spellings& property, int& value) {
    const std::string name(property.canonical());
    if (auto n = numberInput(name.c_str(), shadingSamplesField(name), value, 1, 8)) value = int(*n);
  };
  if (d.usesMisAxes()) {
    count(kLightSamplesProperty, d.lightSamples);
    count(kBsdfSamplesProperty, d.bsdfSamples);
  } else if (d.usesSamples()) {
    count(rowOf(d.type).samplesProperty, d.samples);
  } else {
    ImGui::AlignTextToFramePadding();
    ImGui::TextDisabled("(no shading samples)");
  }
  padBlockTo(top, 2.f * frameRowHeight() + textBlockHeight(" "));  // and a clamped field's note
}

void compareSection(ViewerController& c) {
  ImGui::Separator();
  ImGui::TextUnformatted("Compare");
  const float top = ImGui::GetCursorPosY();
  if (!c.compareOffered()) {  // e.g. simple, normals: nothing to compare with
    hintText("%s has no sampling strategies to compare", strategyLabel(c.settings().integrator).c_str());
    if (c.compareEnabled()) c.setCompare(false);
    padBlockTo(top,
               4.f * frameRowHeight());  // the rows the checkbox and the right side's axes take otherwise
    return;
  }
  bool on = c.compareEnabled();
  if (ImGui::Checkbox("split view", &on)) c.setCompare(on);
  // The right side's axes, as the left side's; only what the scene can render is offered, and the
  // label says exactly what the right side renders.
  IntegratorDesc r = c.compareIntegrator();
  const std::function<std::string(const IntegratorDesc&)> reason = [&](const IntegratorDesc& x) {
    return c.comparableWithLeft(x) ? std::string() : c.strategyUnavailableReason(x);
  };
  const float measureTop = ImGui::GetCursorPosY();
  if (r.usesEstimator()) {
    measureCombo("right side", r, reason);
  } else {
    ImGui::AlignTextToFramePadding();
    ImGui::TextDisabled("right side: %s", strategyLabel(c.renderedCompareIntegrator()).c_str());
  }
  padBlockTo(measureTop, frameRowHeight());
  axisBlock(c, r, "##right", false);
  padBlockTo(top, 4.f * frameRowHeight());
  if (!(r == c.compareIntegrator()) && c.comparableWithLeft(r)) c.setCompareIntegrator(r);
  if (c.compareEnabled()) {
    float pct = c.display.compareDivider * 100.f;
    if (numberSlider("divider", fields::kDividerPercent, pct, 0.f, 100.f, "%.0f %%"))
      c.display.compareDivider = pct / 100.f;
    hintText("%d thread(s) per side, equal time; drag the line in the image", c.engineThreads());
  }
}

}  // namespace

void drawIntegratorPanel(ViewerController& c, PanelState&) {
  if (!ImGui::CollapsingHeader("Integrator", ImGuiTreeNodeFlags_DefaultOpen)) return;
  RenderSettings s = c.settings();
  IntegratorDesc& d = s.integrator;
  const std::function<std::string(const IntegratorDesc&)> reason = [&](const IntegratorDesc& x) {
    return c.strategyUnavailableReason(applicableStrategy(x, c.sceneHasAreaLights()));
  };
  tableCombo(std::string("integrator").c_str(), kIntegratorTypes, &IntegratorTypeRow::type,
             &IntegratorTypeRow::xmlType, d, &IntegratorDesc::type, reason);
  const float measureTop = ImGui::GetCursorPosY();
  if (d.usesEstimator()) {
    measureCombo("measure", d, [&](const IntegratorDesc& x) { return c.strategyUnavailableReason(x); });
  } else {
    ImGui::AlignTextToFramePadding();
    ImGui::TextDisabled("(no measure)");
  }
  padBlockTo(measureTop, frameRowHeight());
  axisBlock(c, d, "", true);

  // The note on the strategy (what renders instead, or why it cannot light the scene): as tall as
  // the tallest note any strategy has on this scene.
  float noteHeight = textBlockHeight(" ");
  for (const IntegratorDesc& x : everyStrategy())
    noteHeight = std::max(noteHeight, textBlockHeight(strategyNote(c, x).c_str()));
  const float top = ImGui::GetCursorPosY();
  const std::string note = strategyNote(c, d);
  if (!note.empty()) hintText("%s", note.c_str());
  padBlockTo(top, noteHeight);
  d = applicableStrategy(d, c.sceneHasAreaLights());

  countsBlock(d);
  c.setSettings(s);  // restarts only if something changed
  compareSection(c);
}

}  // namespace penumbra::ui
