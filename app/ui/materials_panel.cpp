#include <cstdio>
#include <string>

#include <imgui.h>

#include "app/ui/number_input.h"
#include "app/ui/panel_text.h"
#include "app/ui/panels.h"

namespace penumbra::ui {

namespace {

// A float as scene text that reads back as a float (never an integer literal: "1" would make a new
// property an integer).
std::string floatText(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  std::string s = buf;
  if (s.find_first_of(".eE") == std::string::npos) s += ".0";
  return s;
}

}  // namespace

void drawMaterialsPanel(ViewerController& c, PanelState&) {
  const std::vector<GlossyBsdfEntry>& entries = c.glossyBsdfEntries();
  if (entries.empty()) return;  // diffuse scenes: nothing to edit
  if (!ImGui::CollapsingHeader("Materials", ImGuiTreeNodeFlags_DefaultOpen)) return;
  hintText("(glossy BSDFs; an edit rebuilds the scene and lasts until a reload; Save as keeps it)");
  for (size_t i = 0; i < entries.size(); ++i) {
    // Copies: an edit rebuilds the list.
    const std::string label = entries[i].label;
    const Bsdf b = entries[i].bsdf;
    ImGui::PushID(int(i));
    ImGui::TextWrapped("%s: %s", label.c_str(),
                       b.type == BsdfType::Microfacet ? "microfacet" : "roughconductor");
    if (auto a = numberInput("alpha", fields::kAlpha, b.alpha, 0.01, 0.1))
      c.setBsdfProperty(i, "alpha", floatText(*a));
    if (b.type == BsdfType::Microfacet) {
      const bool grey = b.albedo.x == b.albedo.y && b.albedo.y == b.albedo.z;
      if (grey) {
        if (auto kd = numberInput("kd", fields::kReflectance, b.albedo.x, 0.05, 0.2)) {
          const std::string v = floatText(*kd);
          c.setBsdfProperty(i, "kd", v + ", " + v + ", " + v);
        }
      } else {
        hintText("kd %.3g, %.3g, %.3g (a colour: edit it in the file)", b.albedo.x, b.albedo.y, b.albedo.z);
      }
    } else {
      int d = b.distribution == MicrofacetDistribution::Ggx ? 1 : 0;
      const char* names[] = {"beckmann", "ggx"};
      if (ImGui::Combo("distribution", &d, names, 2)) c.setBsdfProperty(i, "distribution", names[d]);
    }
    ImGui::PopID();
  }
}

}  // namespace penumbra::ui
