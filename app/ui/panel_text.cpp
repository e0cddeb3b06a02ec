#include "app/ui/panel_text.h"

#include <cstdarg>

#include <imgui.h>

namespace penumbra::ui {

void hintText(const char* fmt, ...) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::PushTextWrapPos(0.f);
  va_list args;
  va_start(args, fmt);
  ImGui::TextV(fmt, args);
  va_end(args);
  ImGui::PopTextWrapPos();
  ImGui::PopStyleColor();
}

}  // namespace penumbra::ui
