#include <algorithm>
#include <cmath>
#include <cstdint>

#include <imgui.h>

#include "app/ui/light_share_map.h"
#include "app/ui/number_input.h"
#include "app/ui/panel_text.h"
#include "app/ui/panels.h"
#include "app/ui/readouts.h"

namespace penumbra::ui {

namespace {

ImU32 rgbOf(const std::uint8_t rgb[3]) {
  return IM_COL32(rgb[0], rgb[1], rgb[2], 255);
}

// The light-share map's legend: a bar from 0 (cosine) to 1 (light sampling) and the "no area light"
// swatch (app/ui/light_share_map.h).
void drawLightShareLegend() {
  const float width = std::max(ImGui::GetContentRegionAvail().x, 60.f),
              height = ImGui::GetFrameHeight() * 0.6f;
  const ImVec2 p = ImGui::GetCursorScreenPos();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const int segments = 16;
  for (int i = 0; i < segments; ++i) {
    std::uint8_t a[3], b[3];
    lightShareRgb(float(i) / segments, a);
    lightShareRgb(float(i + 1) / segments, b);
    const float x0 = p.x + width * i / segments, x1 = p.x + width * (i + 1) / segments;
    dl->AddRectFilledMultiColor(ImVec2(x0, p.y), ImVec2(x1, p.y + height), rgbOf(a), rgbOf(b), rgbOf(b),
                                rgbOf(a));
  }
  ImGui::Dummy(ImVec2(width, height));
  ImGui::TextUnformatted("0 cosine");
  const char* mid = "0.5";
  ImGui::SameLine(width * 0.5f - ImGui::CalcTextSize(mid).x * 0.5f);
  ImGui::TextUnformatted(mid);
  const char* right = "light 1";
  ImGui::SameLine(width - ImGui::CalcTextSize(right).x);
  ImGui::TextUnformatted(right);
  const ImVec2 q = ImGui::GetCursorScreenPos();
  const float side = ImGui::GetTextLineHeight();
  dl->AddRectFilled(q, ImVec2(q.x + side, q.y + side), rgbOf(kNoShareRgb));
  ImGui::Dummy(ImVec2(side, side));
  ImGui::SameLine();
  hintText("no reflected area light (sky, full shadow, the lights)");
}

}  // namespace

void drawDisplayPanel(ViewerController& c, PanelState& st) {
  if (!ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen)) return;
  DisplaySettings& d = c.display;
  // What the image shows: the estimate, or (mis strategies) each pixel's MIS light share, which
  // renders the strategy's split output (a restart).
  const bool offered = c.lightShareOffered();
  int view = c.lightShareView() ? 1 : 0;
  const char* views[] = {"colour", "MIS light share"};
  ImGui::BeginDisabled(!offered);
  if (ImGui::Combo("view", &view, views, offered ? 2 : 1)) c.setLightShareView(view == 1);
  ImGui::EndDisabled();
  if (!offered && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("MIS light share: with a mis strategy, outside compare mode");
  const bool share = c.lightShareView();
  if (share) {
    ImGui::PushTextWrapPos(0.f);
    hintText(
        "share of each pixel's area-light estimate that light sampling contributed "
        "(the rest: cosine-hemisphere directions)");
    ImGui::PopTextWrapPos();
    drawLightShareLegend();
  }
  numberSlider("exposure", fields::kExposure, d.exposure, -10.f, 10.f, "%+.2f stops");
  int tm = int(d.tonemap);
  const char* tms[] = {"sRGB", "gamma 2.2"};
  if (ImGui::Combo("tonemap", &tm, tms, 2)) d.tonemap = Tonemap(tm);
  int fc = int(d.falseColour);
  const char* fcs[] = {"none", "relative std. error", "NaN/Inf/negative"};
  ImGui::BeginDisabled(share);
  if (ImGui::Combo("false colour", &fc, fcs, 3)) d.falseColour = FalseColour(fc);
  ImGui::EndDisabled();
  if (!share && d.falseColour == FalseColour::RelativeError) hintText("log scale: blue 0.1%% .. red 100%%");
  if (!share && d.falseColour == FalseColour::BadPixels) hintText("magenta: NaN/Inf, cyan: negative");
  float zoomLog = std::log2(d.zoom);
  if (numberSlider("zoom", fields::kZoomStops, zoomLog, -4.f, 4.f, "")) {
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
  if (st.hoverValid && !snap.mean.empty() && c.snapshotIsLightShare()) {
    const Color3 v = snap.mean.at(st.hoverX, st.hoverY);
    ImGui::Text("pixel (%d, %d), %u spp", st.hoverX, st.hoverY, snap.spp);
    const float share = lightShare(v);
    if (share >= 0.f)
      ImGui::Text("light share %.3f", share);
    else
      ImGui::TextUnformatted("light share: no area light");
    ImGui::Text("light %.5g  cosine %.5g", v.x, v.y);
    ImGui::Text("rest (lights seen, point/directional) %.5g", v.z);
  } else if (st.hoverValid && !snap.mean.empty()) {
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
      "scene with the live settings; mesh paths are rewritten to load from there. Replacing a file "
      "takes a second press.");
  ImGui::PopTextWrapPos();
  ImGui::SetNextItemWidth(-70);
  ImGui::InputText("##savescene", st.sceneSavePath, sizeof st.sceneSavePath);
  ImGui::SameLine();
  if (ImGui::Button("Save as")) {
    try {
      if (st.sceneSaveGuard.allows(st.sceneSavePath))
        c.setOutputStatus(c.saveSceneAs(st.sceneSavePath));
      else
        c.setOutputStatus(OverwriteGuard::refusal(st.sceneSavePath, "Save as"));
    } catch (const std::exception& e) {
      c.setOutputStatus(e.what());
    }
  }
  if (!c.outputStatus().empty()) ImGui::TextWrapped("%s", c.outputStatus().c_str());
}

}  // namespace penumbra::ui
