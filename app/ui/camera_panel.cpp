#include <imgui.h>

#include "app/ui/panels.h"

namespace penumbra::ui {

void drawCameraPanel(ViewerController& c, PanelState&) {
  if (!ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) return;
  float fov = c.settings().camera.fovDegrees;
  if (ImGui::SliderFloat("fov", &fov, 5.f, 120.f, "%.1f deg")) c.setFov(fov);
  const glm::mat4& m = c.settings().camera.toWorld;
  ImGui::Text("origin %.3g %.3g %.3g", m[3].x, m[3].y, m[3].z);
  const OrbitCamera& o = c.orbitCamera();
  ImGui::Text("target %.3g %.3g %.3g  (dist %.3g)", o.target.x, o.target.y, o.target.z, o.distance);
  if (ImGui::Button("Reset to the scene's camera")) c.resetCamera();
  ImGui::TextDisabled("left drag: orbit, right/middle drag: pan, wheel: dolly");
}

}  // namespace penumbra::ui
