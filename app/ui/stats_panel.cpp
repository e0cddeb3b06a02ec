#include <string>

#include <imgui.h>

#include "app/ui/panel_text.h"
#include "app/ui/panels.h"

namespace penumbra::ui {

void drawStatsPanel(ViewerController& c, PanelState& st) {
  if (!ImGui::CollapsingHeader("Stats", ImGuiTreeNodeFlags_DefaultOpen)) return;
  RenderProgress p = c.progress();
  const RenderLimits l = c.effectiveLimits();
  if (l.targetSpp > 0)
    ImGui::Text("spp %u / %u", p.spp, l.targetSpp);
  else
    ImGui::Text("spp %u", p.spp);
  ImGui::Text("elapsed %.2f s%s", p.seconds,
              c.paused()   ? " (paused: Space resumes)"
              : p.finished ? " (done)"
                           : "");
  if (c.paused())
    hintText("samples/s: none while paused");
  else
    ImGui::Text("samples/s %.3g M", p.seconds > 0 ? double(p.samples) / p.seconds * 1e-6 : 0.0);
  ImGui::Text("NaN/Inf/negative %llu", (unsigned long long)p.badSamples);
  ImGui::Text("%s, %d threads, UI frame %.1f ms", strategyLabel(c.settings().integrator).c_str(),
              c.engine().threadCount(), st.frameMs);
  if (ImGui::TreeNode("Live settings as scene XML")) {
    static std::string xml;
    xml = c.liveSceneXml();
    if (ImGui::Button("Copy")) ImGui::SetClipboardText(xml.c_str());
    ImGui::InputTextMultiline("##xml", xml.data(), xml.size() + 1,
                              ImVec2(-1, ImGui::GetTextLineHeight() * 16), ImGuiInputTextFlags_ReadOnly);
    ImGui::TreePop();
  }
}

}  // namespace penumbra::ui
