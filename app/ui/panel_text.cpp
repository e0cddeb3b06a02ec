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

float textBlockHeight(const char* text) {
  return ImGui::CalcTextSize(text, nullptr, false, ImGui::GetContentRegionAvail().x).y +
         ImGui::GetStyle().ItemSpacing.y;
}

float frameRowHeight() {
  return ImGui::GetFrameHeightWithSpacing();
}

void padBlockTo(float top, float height) {
  if (ImGui::GetCursorPosY() < top + height) ImGui::SetCursorPosY(top + height);
}

}  // namespace penumbra::ui
