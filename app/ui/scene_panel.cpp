#include <cstring>
#include <filesystem>

#include <imgui.h>

#include "app/ui/panel_text.h"
#include "app/ui/panels.h"

namespace penumbra::ui {

void drawScenePanel(ViewerController& c, PanelState& st) {
  if (!ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const LoadedScene& s = c.scene();
  ImGui::TextWrapped("%s", s.path.empty() ? "<built-in default scene>" : s.path.c_str());
  ImGui::SetNextItemWidth(-60);
  bool enter =
      ImGui::InputText("##open", st.openPath, sizeof st.openPath, ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if ((ImGui::Button("Open") || enter) && st.openPath[0]) c.openSceneAsync(st.openPath);
  if (ImGui::Button("Reload")) c.reloadScene();
  ImGui::SameLine();
  hintText("(auto-reloads on change, keeping your changes; drop a file to open)");
  // One line always: loading, loaded in, reloaded (and what was kept).
  ImGui::PushTextWrapPos(0.f);
  if (c.loading())
    ImGui::TextColored(ImVec4(1.f, 0.8f, 0.3f, 1.f), "loading %s ...", c.loadingPath().c_str());
  else
    hintText("%s", c.sceneStatus().empty() ? " " : c.sceneStatus().c_str());
  ImGui::PopTextWrapPos();
  if (!c.sceneError().empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.f, 0.45f, 0.4f, 1.f));
    ImGui::TextWrapped("%s", c.sceneError().c_str());
    ImGui::PopStyleColor();
    hintText("(still rendering the last good scene)");
  }
  if (ImGui::TreeNode("Recent and nearby scenes")) {
    std::string pick;
    for (const std::string& r : c.recentFiles())
      if (ImGui::Selectable(r.c_str(), r == s.path)) pick = r;
    ImGui::Separator();
    for (const std::string& f : c.siblingScenes()) {
      std::string label = std::filesystem::path(f).filename().string();
      if (ImGui::Selectable(label.c_str())) pick = f;
    }
    if (!pick.empty()) {
      std::strncpy(st.openPath, pick.c_str(), sizeof st.openPath - 1);
      c.openSceneAsync(pick);
    }
    ImGui::TreePop();
  }
  if (!s.warnings.empty() && ImGui::TreeNode("Warnings", "Warnings (%d)", int(s.warnings.size()))) {
    for (const std::string& w : s.warnings) ImGui::TextWrapped("%s", w.c_str());
    ImGui::TreePop();
  }
}

}  // namespace penumbra::ui
