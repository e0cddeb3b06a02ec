// Convergence panel: RMSE against elapsed seconds of the current accumulation, log-log,
// with the curves of the strategies tried earlier (on the same scene and camera) kept
// beside it. Drawn with
// ImDrawList; the numbers come from ConvergenceTracker (no GL there).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "app/ui/panel_text.h"
#include "app/ui/panels.h"

namespace penumbra::ui {

namespace {

const ImU32 kCurveColours[] = {IM_COL32(230, 159, 0, 255), IM_COL32(86, 180, 233, 255),
                               IM_COL32(0, 158, 115, 255), IM_COL32(240, 228, 66, 255),
                               IM_COL32(213, 94, 0, 255),  IM_COL32(204, 121, 167, 255)};

void drawPlot(const ConvergenceTracker& t, bool noLight) {
  const auto& curves = t.curves();
  double xmin = INFINITY, xmax = 0, ymin = INFINITY, ymax = 0;
  for (const ConvergenceCurve& c : curves)
    for (std::size_t i = 0; i < c.seconds.size(); ++i) {
      double x = c.seconds[i], y = noLight ? c.rmseNoLight[i] : c.rmse[i];
      if (!(x > 0) || !(y > 0)) continue;
      xmin = std::min(xmin, x), xmax = std::max(xmax, x), ymin = std::min(ymin, y), ymax = std::max(ymax, y);
    }
  if (!(xmax > 0)) {
    hintText("waiting for the first pass...");
    return;
  }
  double lx0 = std::floor(std::log10(xmin)), lx1 = std::max(std::ceil(std::log10(xmax)), lx0 + 1);
  double ly0 = std::floor(std::log10(ymin)), ly1 = std::max(std::ceil(std::log10(ymax)), ly0 + 1);

  ImDrawList* dl = ImGui::GetWindowDrawList();
  ImVec2 p0 = ImGui::GetCursorScreenPos();
  float w = std::max(ImGui::GetContentRegionAvail().x, 120.f), h = 190.f;
  const float left = 44.f, bottom = 18.f;
  ImVec2 a(p0.x + left, p0.y + 4), b(p0.x + w - 6, p0.y + h - bottom);
  auto X = [&](double v) { return float(a.x + (std::log10(v) - lx0) / (lx1 - lx0) * (b.x - a.x)); };
  auto Y = [&](double v) { return float(b.y - (std::log10(v) - ly0) / (ly1 - ly0) * (b.y - a.y)); };
  dl->AddRectFilled(a, b, IM_COL32(25, 25, 28, 255));
  char buf[32];
  for (int k = int(lx0); k <= int(lx1); ++k) {
    float x = X(std::pow(10.0, k));
    dl->AddLine(ImVec2(x, a.y), ImVec2(x, b.y), IM_COL32(70, 70, 75, 255));
    std::snprintf(buf, sizeof buf, "1e%d s", k);
    // Centred under its line, but kept within the plot's width (the last label would pass its edge).
    const float labelX =
        std::min(x - 0.5f * ImGui::CalcTextSize(buf).x, p0.x + w - ImGui::CalcTextSize(buf).x);
    dl->AddText(ImVec2(labelX, b.y + 2), IM_COL32(170, 170, 170, 255), buf);
  }
  for (int k = int(ly0); k <= int(ly1); ++k) {
    float y = Y(std::pow(10.0, k));
    dl->AddLine(ImVec2(a.x, y), ImVec2(b.x, y), IM_COL32(70, 70, 75, 255));
    std::snprintf(buf, sizeof buf, "1e%d", k);
    dl->AddText(ImVec2(p0.x, y - 7), IM_COL32(170, 170, 170, 255), buf);
  }
  // -1/2 slope guide through the newest curve's last point.
  const ConvergenceCurve& last = curves.back();
  if (!last.seconds.empty()) {
    double x1 = last.seconds.back(), y1 = noLight ? last.rmseNoLight.back() : last.rmse.back();
    if (x1 > 0 && y1 > 0) {
      double xa = std::pow(10.0, lx0), xb = std::pow(10.0, lx1);
      dl->PushClipRect(a, b, true);
      dl->AddLine(ImVec2(X(xa), Y(y1 * std::sqrt(x1 / xa))), ImVec2(X(xb), Y(y1 * std::sqrt(x1 / xb))),
                  IM_COL32(140, 140, 140, 160), 1.f);
      dl->PopClipRect();
    }
  }
  dl->PushClipRect(a, b, true);
  for (std::size_t ci = 0; ci < curves.size(); ++ci) {
    const ConvergenceCurve& c = curves[ci];
    ImU32 col = kCurveColours[ci % 6];
    ImVec2 prev;
    bool have = false;
    for (std::size_t i = 0; i < c.seconds.size(); ++i) {
      double y = noLight ? c.rmseNoLight[i] : c.rmse[i];
      if (!(c.seconds[i] > 0) || !(y > 0)) continue;
      ImVec2 p(X(c.seconds[i]), Y(y));
      if (have) dl->AddLine(prev, p, col, ci + 1 == curves.size() ? 2.5f : 1.5f);
      dl->AddCircleFilled(p, 2.5f, col);  // a marker per measurement (a curve may have a single point)
      prev = p;
      have = true;
    }
  }
  dl->PopClipRect();
  dl->AddRect(a, b, IM_COL32(120, 120, 120, 255));
  ImGui::Dummy(ImVec2(w, h));
  // Legend: one line per curve, newest last.
  for (std::size_t ci = 0; ci < curves.size(); ++ci) {
    const ConvergenceCurve& c = curves[ci];
    if (c.seconds.empty()) continue;
    colouredWrappedText(ImGui::ColorConvertU32ToFloat4(kCurveColours[ci % 6]), "%s%s: %.3g at %.2f s, %u spp",
                        c.label.c_str(), ci + 1 == curves.size() ? "*" : "",
                        noLight ? c.rmseNoLight.back() : c.rmse.back(), c.seconds.back(), c.spp.back());
  }
}

}  // namespace

void drawConvergencePanel(ViewerController& c, PanelState& st) {
  ConvergenceTracker& t = st.convergence;
  t.update(c);  // every frame, even when collapsed, so the curve has no gaps
  if (!ImGui::CollapsingHeader("Convergence", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (!t.hasReference()) {
    ImGui::TextWrapped(
        "No reference for this scene and camera. Scenes in scenes/analytic/ use their closed "
        "form; otherwise run `penumbra render --reference SCENE.xml` (writes %s) or load an "
        "EXR/PFM below.",
        t.cachePath().c_str());
  } else {
    ImGui::TextWrapped("reference: %s", t.reference().source.c_str());
    ImGui::Checkbox("only pixels that see no light", &st.convergenceNoLight);
    sameLineIfFits(buttonWidth("Clear curves"));
    if (ImGui::Button("Clear curves")) t.clearCurves();
    drawPlot(t, st.convergenceNoLight);
    hintText("RMSE; *: current; grey: slope -1/2. Switch the strategy to add a curve.");
  }
  if (ImGui::Button("Load reference")) t.loadReference(c, st.referencePath);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1);
  ImGui::InputTextWithHint("##reference", "reference .exr / .pfm", st.referencePath, sizeof st.referencePath);
  if (!t.error().empty()) colouredWrappedText(ImVec4(1, 0.4f, 0.4f, 1), "%s", t.error().c_str());
}

}  // namespace penumbra::ui
