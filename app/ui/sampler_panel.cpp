#include <algorithm>
#include <string>

#include <imgui.h>

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
  if (!c.samplerNote().empty()) ImGui::TextWrapped("%s", c.samplerNote().c_str());
  int count = int(s.sampleCount);
  if (ImGui::InputInt("sampleCount", &count, 1, 16, ImGuiInputTextFlags_EnterReturnsTrue))
    s.sampleCount = uint32_t(std::clamp(count, 1, 1 << 24));
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        samplerRow(s.samplerKind).usesSampleCount
            ? "The scene's <sampler sampleCount>: this sampler's strata, and the default target spp.\n"
              "While the target spp equals it, the target follows it."
            : "The scene's <sampler sampleCount>: the default target spp (this sampler ignores it).\n"
              "While the target spp equals it, the target follows it.");
  int seed = int(s.seed);
  if (ImGui::InputInt("seed", &seed, 1, 10, ImGuiInputTextFlags_EnterReturnsTrue))
    s.seed = uint64_t(std::max(seed, 0));
  c.setSettings(s);

  RenderLimits l = c.limits();
  int mode = l.seconds > 0 ? 1 : 0;
  ImGui::RadioButton("target spp", &mode, 0);
  ImGui::SameLine();
  ImGui::RadioButton("time budget", &mode, 1);
  if (mode == 0) {
    int spp = int(l.targetSpp);
    // "##value": the radio button above is also labelled "target spp"; with one ID ImGui takes the two
    // for one widget, and a click in this box trips its assert.
    if (ImGui::InputInt("target spp##value", &spp, 16, 256, ImGuiInputTextFlags_EnterReturnsTrue) ||
        l.seconds > 0) {
      l.targetSpp = uint32_t(std::max(spp, 0));
      l.seconds = 0;
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("When the accumulation stops (0: never). This, not sampleCount, stops the render.");
  } else {
    float sec = l.seconds > 0 ? float(l.seconds) : 10.f;
    if (ImGui::InputFloat("seconds", &sec, 1.f, 10.f, "%.1f", ImGuiInputTextFlags_EnterReturnsTrue) ||
        l.seconds <= 0) {
      l.seconds = std::max(sec, 0.1f);
      l.targetSpp = 0;
    }
  }
  c.setLimits(l);
  hintText("%s", c.stopText().c_str());

  if (ImGui::Button(c.paused() ? "Resume (space)" : "Pause (space)")) c.setPaused(!c.paused());
  ImGui::SameLine();
  if (ImGui::Button("Restart (R)")) c.restart();  // resumes when paused
}

}  // namespace penumbra::ui
