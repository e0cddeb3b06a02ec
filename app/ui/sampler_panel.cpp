#include <algorithm>
#include <string>

#include <imgui.h>

#include "app/ui/number_input.h"
#include "app/ui/panel_text.h"
#include "app/ui/panels.h"

namespace penumbra::ui {

void drawSamplerPanel(ViewerController& c, PanelState&) {
  if (!ImGui::CollapsingHeader("Sampler", ImGuiTreeNodeFlags_DefaultOpen)) return;
  RenderSettings s = c.settings();
  // Every sampler of the table, in its order.
  if (ImGui::BeginCombo("sampler", std::string(samplerRow(s.samplerKind).label).c_str())) {
    for (const SamplerRow& row : samplerTable()) {
      if (ImGui::Selectable(std::string(row.label).c_str(), row.kind == s.samplerKind))
        s.samplerKind = row.kind;
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", std::string(row.description).c_str());
    }
    ImGui::EndCombo();
  }
  if (!c.samplerNote().empty()) hintText("%s", c.samplerNote().c_str());
  if (auto count = numberInput("sampleCount", fields::kSampleCount, s.sampleCount, 1, 16))
    s.sampleCount = uint32_t(*count);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        samplerRow(s.samplerKind).usesSampleCount()
            ? "The scene's <sampler sampleCount>: this sampler's strata, and the default target spp.\n"
              "While the target spp equals it, the target follows it."
            : "The scene's <sampler sampleCount>: the default target spp (this sampler ignores it).\n"
              "While the target spp equals it, the target follows it.");
  if (auto seed = numberInput("seed", fields::kSeed, double(s.seed), 1, 10)) s.seed = uint64_t(*seed);
  c.setSettings(s);

  // What stops the render; each rule keeps its value while the other rules.
  const StopRule rule = c.stopRule();
  if (ImGui::RadioButton("target spp##stop-rule", rule == StopRule::TargetSpp))
    c.setStopRule(StopRule::TargetSpp);
  sameLineIfFits(radioButtonWidth("time budget##stop-rule"));
  if (ImGui::RadioButton("time budget##stop-rule", rule == StopRule::TimeBudget))
    c.setStopRule(StopRule::TimeBudget);
  if (c.stopRule() == StopRule::TargetSpp) {
    if (auto spp = numberInput("target spp", fields::kTargetSpp, c.limits().targetSpp, 16, 256))
      c.setTargetSpp(uint32_t(*spp));
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("When the accumulation stops (0: never). This, not sampleCount, stops the render.");
  } else {
    if (auto seconds = numberInput("seconds", fields::kSeconds, c.limits().seconds, 1, 10))
      c.setTimeBudget(*seconds);
  }
  hintText("%s", c.stopText().c_str());

  if (ImGui::Button(c.paused() ? "Resume (space)" : "Pause (space)")) c.setPaused(!c.paused());
  sameLineIfFits(buttonWidth("Restart (R)"));
  if (ImGui::Button("Restart (R)")) c.restart();  // resumes when paused
}

}  // namespace penumbra::ui
