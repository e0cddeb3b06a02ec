#include <imgui.h>

#include "app/ui/key_bindings.h"
#include "app/ui/panels.h"

namespace penumbra::ui {

void drawHelpPanel(ViewerController&, PanelState& st) {
  if (!st.showHelp) return;
  ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x * 0.5f, ImGui::GetIO().DisplaySize.y * 0.5f),
                          ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (ImGui::Begin("Help", &st.showHelp, ImGuiWindowFlags_AlwaysAutoResize)) {
    if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg)) {
      for (const KeyBinding& b : keyBindings()) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(b.label);
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(b.help);
      }
      ImGui::EndTable();
    }
    ImGui::TextDisabled("Changes to integrator, sampler, seed or camera restart accumulation;");
    ImGui::TextDisabled("exposure, tonemap, false colour and zoom never do.");
  }
  ImGui::End();
}

}  // namespace penumbra::ui
