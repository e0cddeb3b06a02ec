#include <imgui.h>

#include "app/ui/panels.h"

namespace penumbra::ui {

const Shortcut kShortcuts[] = {
    {"Space", "pause / resume"},
    {"R", "restart accumulation"},
    {"S", "save the display as PNG (path in the Display panel)"},
    {"F", "fit the image to the window / reset pan"},
    {"+ / -", "exposure up / down by 1/2 stop"},
    {"H", "show / hide this help"},
    {"left drag", "orbit the camera about its target"},
    {"left drag on the divider", "compare mode: move the split line"},
    {"right / middle drag", "pan the camera"},
    {"wheel", "dolly (Ctrl + wheel: zoom the display)"},
};
const int kShortcutCount = int(sizeof kShortcuts / sizeof kShortcuts[0]);

void drawHelpPanel(ViewerController&, PanelState& st) {
  if (!st.showHelp) return;
  ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x * 0.5f, ImGui::GetIO().DisplaySize.y * 0.5f),
                          ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (ImGui::Begin("Help", &st.showHelp, ImGuiWindowFlags_AlwaysAutoResize)) {
    if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg)) {
      for (int i = 0; i < kShortcutCount; ++i) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(kShortcuts[i].key);
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(kShortcuts[i].action);
      }
      ImGui::EndTable();
    }
    ImGui::TextDisabled("Changes to integrator, sampler, seed or camera restart accumulation;");
    ImGui::TextDisabled("exposure, tonemap, false colour and zoom never do.");
  }
  ImGui::End();
}

}  // namespace penumbra::ui
