#include "app/ui/number_input.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <unordered_map>

#include "app/ui/panel_text.h"

namespace penumbra::ui {

namespace {

struct FieldState {
  char text[64] = "";
  bool editing = false;  // ImGui owns the text while the field is active
  std::string note;
};

std::unordered_map<ImGuiID, FieldState>& fieldStates() {
  static std::unordered_map<ImGuiID, FieldState> states;
  return states;
}

void showNote(const FieldState& st) {
  if (!st.note.empty()) hintText("%s", st.note.c_str());
}

}  // namespace

std::optional<double> numberInput(const char* label, const NumberField& field, double current, double step,
                                  double fastStep) {
  ImGui::PushID(label);
  FieldState& st = fieldStates()[ImGui::GetID("##state")];
  if (!st.editing) std::snprintf(st.text, sizeof st.text, "%s", formatNumber(current, field).c_str());
  const ImGuiStyle& style = ImGui::GetStyle();
  const float button = ImGui::GetFrameHeight();
  ImGui::SetNextItemWidth(std::max(1.f, ImGui::CalcItemWidth() - 2.f * (button + style.ItemInnerSpacing.x)));
  ImGui::InputText("##text", st.text, sizeof st.text, ImGuiInputTextFlags_CharsScientific);
  st.editing = ImGui::IsItemActive();
  std::optional<double> entered;
  auto take = [&](const NumberEntry& e) {
    st.note = e.note;
    if (e.value && *e.value != current) entered = e.value;
  };
  if (ImGui::IsItemDeactivatedAfterEdit()) take(parseNumberEntry(st.text, field, current));
  const double by = ImGui::GetIO().KeyCtrl ? fastStep : step;
  ImGui::PushButtonRepeat(true);
  ImGui::SameLine(0, style.ItemInnerSpacing.x);
  if (ImGui::Button("-##less", ImVec2(button, button))) take(clampNumber(current - by, field, current));
  ImGui::SameLine(0, style.ItemInnerSpacing.x);
  if (ImGui::Button("+##more", ImVec2(button, button))) take(clampNumber(current + by, field, current));
  ImGui::PopButtonRepeat();
  const char* shownEnd = std::strstr(label, "##");
  if (shownEnd != label) {
    ImGui::SameLine(0, style.ItemInnerSpacing.x);
    ImGui::TextUnformatted(label, shownEnd);
  }
  ImGui::PopID();
  showNote(st);
  return entered;
}

bool numberSlider(const char* label, const NumberField& field, float& value, float dragMin, float dragMax,
                  const char* format, int sliderFlags) {
  FieldState& st = fieldStates()[ImGui::GetID(label)];  // the slider's own ID
  float v = value;
  bool changed = ImGui::SliderFloat(label, &v, dragMin, dragMax, format, sliderFlags);
  if (changed) {
    NumberEntry e = clampNumber(v, field, value);
    st.note = e.note;
    changed = e.value.has_value() && float(*e.value) != value;
    if (e.value) value = float(*e.value);
  }
  showNote(st);
  return changed;
}

void forgetNumberNotes() {
  for (auto& [id, st] : fieldStates()) st.note.clear();
}

}  // namespace penumbra::ui
