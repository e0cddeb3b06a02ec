#include <algorithm>

#include <imgui.h>

#include "app/ui/panels.h"

namespace penumbra::ui {

void drawIntegratorPanel(ViewerController& c, PanelState&) {
  if (!ImGui::CollapsingHeader("Integrator", ImGuiTreeNodeFlags_DefaultOpen)) return;
  RenderSettings s = c.settings();
  IntegratorDesc& d = s.integrator;
  const bool areaLights = c.sceneHasAreaLights();

  int type = d.type == IntegratorType::Ao        ? 0
             : d.type == IntegratorType::Direct  ? 1
             : d.type == IntegratorType::Normals ? 2
                                                 : 3;
  const char* types[] = {"ao", "direct", "normals", "simple"};
  if (ImGui::Combo("integrator", &type, types, 4)) {
    d.type = type == 0   ? IntegratorType::Ao
             : type == 1 ? IntegratorType::Direct
             : type == 2 ? IntegratorType::Normals
                         : IntegratorType::Simple;
    if (d.type == IntegratorType::Direct && !areaLights) d.measure = DirectMeasure::Hemisphere;
  }

  if (d.type == IntegratorType::Direct) {
    // Light measures only when the scene has area lights to sample.
    if (areaLights) {
      int m = int(d.measure);
      const char* measures[] = {"hemisphere", "area", "solid-angle"};
      if (ImGui::Combo("measure", &m, measures, 3)) d.measure = DirectMeasure(m);
    } else {
      ImGui::TextDisabled("measure: hemisphere (no area lights)");
      d.measure = DirectMeasure::Hemisphere;
    }
  }
  bool showWarp = d.type == IntegratorType::Ao ||
                  (d.type == IntegratorType::Direct && d.measure == DirectMeasure::Hemisphere);
  if (showWarp) {
    int w = int(d.warp);
    const char* warps[] = {"uniform-hemisphere", "cosine-hemisphere"};
    if (ImGui::Combo("warp", &w, warps, 2)) d.warp = HemisphereWarp(w);
  }
  if (d.type == IntegratorType::Ao || d.type == IntegratorType::Direct) {
    int n = d.samples;
    const char* label = d.type == IntegratorType::Ao ? "shadingSamples" : "nSamples";
    if (ImGui::InputInt(label, &n, 1, 8, ImGuiInputTextFlags_EnterReturnsTrue) ||
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
  // The strategies of `direct` and `ao` (the same scene, camera and sampler as the left side).
  struct Choice {
    const char* label;
    IntegratorDesc desc;
  };
  const Choice choices[] = {
      {"direct/uniform-hemisphere",
       {IntegratorType::Direct, r.samples, DirectMeasure::Hemisphere, HemisphereWarp::Uniform}},
      {"direct/cosine-hemisphere",
       {IntegratorType::Direct, r.samples, DirectMeasure::Hemisphere, HemisphereWarp::Cosine}},
      {"direct/area", {IntegratorType::Direct, r.samples, DirectMeasure::Area, r.warp}},
      {"direct/solid-angle", {IntegratorType::Direct, r.samples, DirectMeasure::SolidAngle, r.warp}},
      {"ao/uniform", {IntegratorType::Ao, r.samples, r.measure, HemisphereWarp::Uniform}},
      {"ao/cosine", {IntegratorType::Ao, r.samples, r.measure, HemisphereWarp::Cosine}},
  };
  int current = -1;
  for (int i = 0; i < 6; ++i) {
    const IntegratorDesc& d = choices[i].desc;
    bool hemi = d.type == IntegratorType::Ao || d.measure == DirectMeasure::Hemisphere;
    if (d.type == r.type && d.measure == r.measure && (!hemi || d.warp == r.warp)) current = i;
  }
  if (ImGui::BeginCombo("right side", current >= 0 ? choices[current].label : strategyLabel(r).c_str())) {
    for (int i = 0; i < 6; ++i) {
      bool needsLights = choices[i].desc.type == IntegratorType::Direct &&
                         choices[i].desc.measure != DirectMeasure::Hemisphere;
      if (needsLights && !areaLights) continue;
      if (ImGui::Selectable(choices[i].label, i == current)) c.setCompareIntegrator(choices[i].desc);
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
