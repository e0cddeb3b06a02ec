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
}

}  // namespace penumbra::ui
