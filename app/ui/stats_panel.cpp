#include <algorithm>
#include <string>

#include <imgui.h>

#include "app/ui/panel_text.h"
#include "app/ui/panels.h"
#include "app/ui/readouts.h"

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
    ImGui::Text("samples/s %.3g M", samplesPerSecond(p, c.settings().camera.width) * 1e-6);
  // One line always: how far a slow pass got (a first pass of 65536 shading samples takes seconds).
  const std::string pass = passProgressText(p);
  hintText("%s", pass.empty() ? " " : pass.c_str());
  ImGui::Text("NaN/Inf/negative %llu", (unsigned long long)p.badSamples);
  // The strategy on a line as tall as the longest label needs (it wraps in a narrow column), so the
  // sections below stay put when it changes.
  float labelHeight = 0.f;
  for (const IntegratorDesc& d : everyStrategy())
    labelHeight = std::max(labelHeight, textBlockHeight(strategyLabel(d).c_str()));
  const float top = ImGui::GetCursorPosY();
  ImGui::TextUnformatted(strategyLabel(c.settings().integrator).c_str());
  padBlockTo(top, labelHeight);
  ImGui::Text("%d threads, UI frame %.1f ms", c.engine().threadCount(), st.frameMs);
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
