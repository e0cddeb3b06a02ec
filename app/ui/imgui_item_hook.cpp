// Link-time wrappers (ld --wrap, set up for penumbra-offscreen in CMakeLists.txt) around two functions
// of Debian's static Dear ImGui: ImGui::ItemAdd, where every widget registers its ID and rectangle,
// and ImGuiWindow::GetID(label), where a label becomes an ID. They record into activeItemLog()
// (app/ui/item_log.h) and otherwise change nothing. Only calls from imgui_widgets.cpp and
// imgui_tables.cpp pass through a wrapper (calls inside imgui.cpp are resolved by the compiler):
// that is every widget; what stays unseen are the items imgui.cpp adds itself (groups, child windows).
#include <imgui.h>
#include <imgui_internal.h>

#include "app/ui/item_log.h"

extern "C" {
bool __real__ZN5ImGui7ItemAddERK6ImRectjPS1_i(const ImRect& bb, ImGuiID id, const ImRect* navBb,
                                              ImGuiItemFlags flags);
ImGuiID __real__ZN11ImGuiWindow5GetIDEPKcS1_(ImGuiWindow* window, const char* str, const char* strEnd);

bool __wrap__ZN5ImGui7ItemAddERK6ImRectjPS1_i(const ImRect& bb, ImGuiID id, const ImRect* navBb,
                                              ImGuiItemFlags flags) {
  if (penumbra::ui::ItemLog* log = penumbra::ui::activeItemLog()) {
    const ImGuiWindow* w = ImGui::GetCurrentContext()->CurrentWindow;
    log->add(id, w ? w->ID : 0, w ? w->Name : nullptr, bb.Min.x, bb.Min.y, bb.Max.x, bb.Max.y);
  }
  return __real__ZN5ImGui7ItemAddERK6ImRectjPS1_i(bb, id, navBb, flags);
}

ImGuiID __wrap__ZN11ImGuiWindow5GetIDEPKcS1_(ImGuiWindow* window, const char* str, const char* strEnd) {
  const ImGuiID id = __real__ZN11ImGuiWindow5GetIDEPKcS1_(window, str, strEnd);
  if (penumbra::ui::ItemLog* log = penumbra::ui::activeItemLog()) log->noteLabel(id, str, strEnd);
  return id;
}
}
