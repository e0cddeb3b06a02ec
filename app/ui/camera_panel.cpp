#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "app/ui/number_input.h"
#include "app/ui/panel_text.h"
#include "app/ui/panels.h"

namespace penumbra::ui {

namespace {
// Float noise from deriving a point through the camera matrix (a target of 0 shown as -4.77e-07)
// is shown as 0: below 1e-5 of the camera's scale nothing is meaningful at three digits anyway.
glm::vec3 forDisplay(glm::vec3 p, float scale) {
  for (int i = 0; i < 3; ++i)
    if (std::fabs(p[i]) < 1e-5f * scale) p[i] = 0.f;
  return p;
}
}  // namespace

void drawCameraPanel(ViewerController& c, PanelState&) {
  if (!ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) return;
  float fov = c.settings().camera.fovDegrees;
  if (numberSlider("fov", fields::kFov, fov, 5.f, 120.f, "%.1f deg")) c.setFov(fov);
  const glm::mat4& m = c.settings().camera.toWorld;
  const OrbitCamera& o = c.orbitCamera();
  const float scale = glm::length(glm::vec3(m[3])) + o.distance;
  const glm::vec3 origin = forDisplay(glm::vec3(m[3]), scale), target = forDisplay(c.shownTarget(), scale);
  ImGui::Text("origin %.3g %.3g %.3g", origin.x, origin.y, origin.z);
  ImGui::Text("target %.3g %.3g %.3g  (dist %.3g)", target.x, target.y, target.z, o.distance);
  // Where the camera is relative to the orbit's horizon (the orbit stops at the scene's horizon).
  const glm::vec3 dir = glm::normalize(glm::vec3(m[3]) - c.shownTarget());
  const float elevationDeg = glm::degrees(std::asin(std::clamp(glm::dot(dir, o.worldUp), -1.f, 1.f)));
  ImGui::Text("elevation %.1f deg%s", elevationDeg, o.minElevationSin >= 0.f ? " (orbit stays above 0)" : "");
  if (ImGui::Button("Reset to the scene's camera")) c.resetCamera();
  // The drag help, or why the last move stopped, in a block as tall as the taller of the two.
  const char* help = "left drag: orbit, right/middle drag: pan, wheel: dolly";
  const std::string& note = c.cameraLimitNote();
  const float top = ImGui::GetCursorPosY();
  if (note.empty())
    hintText("%s", help);
  else
    ImGui::TextColored(ImVec4(1.f, 0.8f, 0.3f, 1.f), "%s", note.c_str());
  float height = textBlockHeight(help);
  for (const char* limit : kCameraLimitNotes) height = std::max(height, textBlockHeight(limit));
  padBlockTo(top, height);
}

}  // namespace penumbra::ui
