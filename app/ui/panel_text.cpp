#include "app/ui/panel_text.h"

#include <cstdarg>

#include <imgui.h>

namespace penumbra::ui {

namespace {

void wrappedTextV(const ImVec4& colour, const char* fmt, va_list args) {
  ImGui::PushStyleColor(ImGuiCol_Text, colour);
  ImGui::PushTextWrapPos(0.f);
  ImGui::TextV(fmt, args);
  ImGui::PopTextWrapPos();
  ImGui::PopStyleColor();
}

}  // namespace

void hintText(const char* fmt, ...) {
  va_list args;
  va_start(args, fmt);
  wrappedTextV(ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled), fmt, args);
  va_end(args);
}

void colouredWrappedText(const ImVec4& colour, const char* fmt, ...) {
  va_list args;
  va_start(args, fmt);
  wrappedTextV(colour, fmt, args);
  va_end(args);
}

float buttonWidth(const char* label) {
  return ImGui::CalcTextSize(label, nullptr, true).x + 2.f * ImGui::GetStyle().FramePadding.x;
}

float radioButtonWidth(const char* label) {
  return ImGui::GetFrameHeight() + ImGui::GetStyle().ItemInnerSpacing.x +
         ImGui::CalcTextSize(label, nullptr, true).x;
}

void sameLineIfFits(float width) {
  const float right = ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + width;
  if (right <= ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x) ImGui::SameLine();
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
