#include <cmath>

#include <imgui.h>

#include "app/ui/panel_text.h"
#include "app/ui/panels.h"
#include "app/ui/readouts.h"

namespace penumbra::ui {

void drawDisplayPanel(ViewerController& c, PanelState& st) {
  if (!ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen)) return;
  DisplaySettings& d = c.display;
  ImGui::SliderFloat("exposure", &d.exposure, -10.f, 10.f, "%+.2f stops");
  int tm = int(d.tonemap);
  const char* tms[] = {"sRGB", "gamma 2.2"};
  if (ImGui::Combo("tonemap", &tm, tms, 2)) d.tonemap = Tonemap(tm);
  int fc = int(d.falseColour);
  const char* fcs[] = {"none", "relative std. error", "NaN/Inf/negative"};
  if (ImGui::Combo("false colour", &fc, fcs, 3)) d.falseColour = FalseColour(fc);
  if (d.falseColour == FalseColour::RelativeError) hintText("log scale: blue 0.1%% .. red 100%%");
  if (d.falseColour == FalseColour::BadPixels) hintText("magenta: NaN/Inf, cyan: negative");
  float zoomLog = std::log2(d.zoom);
  if (ImGui::SliderFloat("zoom", &zoomLog, -4.f, 4.f, "")) {
    d.zoom = std::exp2(zoomLog);
    d.fit = false;
  }
  ImGui::SameLine();
  ImGui::TextUnformatted(zoomLabel(d, st.layoutZoom).c_str());
  if (ImGui::Button("1:1")) {
    d.zoom = 1.f;
    d.panX = d.panY = 0.f;
    d.fit = false;
  }
  ImGui::SameLine();
  if (ImGui::Button("Fit (F)")) {
    d.fit = true;
    d.panX = d.panY = 0.f;
  }

  // Pixel inspector: always four lines, so nothing below it moves when the pointer enters the image.
  const FilmSnapshot& snap = c.snapshot();
  if (st.hoverValid && !snap.mean.empty()) {
    Color3 v = snap.mean.at(st.hoverX, st.hoverY);
    ImGui::Text("pixel (%d, %d), %u spp", st.hoverX, st.hoverY, snap.spp);
    const bool probed = snap.probe.x == st.hoverX && snap.probe.y == st.hoverY;
    if (probeHasError(snap.spp) &&
        (probed || (!snap.standardError.empty() && snap.standardError.width == snap.mean.width))) {
      Color3 e = probed ? snap.probe.standardError : snap.standardError.at(st.hoverX, st.hoverY);
      ImGui::Text("R %.5g %s", v.x, probeErrorText(snap.spp, e.x).c_str());
      ImGui::Text("G %.5g %s", v.y, probeErrorText(snap.spp, e.y).c_str());
      ImGui::Text("B %.5g %s", v.z, probeErrorText(snap.spp, e.z).c_str());
    } else {
      ImGui::Text("RGB %.5g %.5g %.5g", v.x, v.y, v.z);
      hintText("%s", probeHasError(snap.spp) ? "(error: next pass)" : probeErrorText(snap.spp, 0).c_str());
      ImGui::TextUnformatted("");
    }
  } else {
    hintText("hover the image to inspect a pixel");
    for (int i = 0; i < 3; ++i) ImGui::TextUnformatted("");
  }

  ImGui::Separator();
  ImGui::SetNextItemWidth(-70);
  ImGui::InputText("##save", st.savePath, sizeof st.savePath);
  ImGui::SameLine();
  if (ImGui::Button("Save")) st.requestSavePng = true;
  ImGui::PushTextWrapPos(0.f);
  hintText(
      ".png: display (exposure applied); .exr/.pfm: accumulation. Save as writes the "
      "scene with the live settings; mesh paths are rewritten to load from there.");
  ImGui::PopTextWrapPos();
  ImGui::SetNextItemWidth(-70);
  ImGui::InputText("##savescene", st.sceneSavePath, sizeof st.sceneSavePath);
  ImGui::SameLine();
  if (ImGui::Button("Save as")) {
    try {
      st.status = c.saveSceneAs(st.sceneSavePath);
    } catch (const std::exception& e) {
      st.status = e.what();
    }
  }
  if (!st.status.empty()) ImGui::TextWrapped("%s", st.status.c_str());
}

}  // namespace penumbra::ui
