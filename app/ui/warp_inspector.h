// The warp inspector window (ImGui + GL): controls, a 3-D view of the warped points rendered into an
// FBO texture (arcball rotate, wheel zoom), and the chi-square panels (histogram, integrated density,
// signed difference) with the verdict. Opened from the viewer's sidebar or by `penumbra warp --gui`.
#pragma once

#include <memory>
#include <string>

#include <glm/gtc/quaternion.hpp>

#include "app/ui/warp_inspector_model.h"

namespace penumbra::ui {

class WarpInspector {
 public:
  explicit WarpInspector(const WarpInspectorSettings& initial = {});  // needs a current GL 3.3 context
  ~WarpInspector();
  WarpInspector(const WarpInspector&) = delete;
  WarpInspector& operator=(const WarpInspector&) = delete;

  // Draws the window. `open` as for ImGui::Begin (nullptr: no close button); `fill`: cover the whole
  // display (the standalone `penumbra warp --gui`).
  void draw(bool* open, bool fill);

  WarpInspectorSettings& settings() { return settings_; }
  const WarpInspectorWorker& worker() const { return worker_; }
  // True when the points and verdict on screen are those of the current settings.
  bool upToDate() const;
  // "panel NAME X Y W H" lines for the three panels and a "verdict ..." line (tests, --print-layout).
  std::string layoutReport() const;

 private:
  void drawControls();
  void drawView(float width, float height);
  void drawPanels(float width);
  void uploadPoints();
  void uploadPanels();
  void renderScene(int width, int height);
  void resetView();

  WarpInspectorSettings settings_;
  std::string refusal_;  // why the last value entered was refused, as `penumbra warp` says it
  WarpInspectorWorker worker_;
  std::shared_ptr<const WarpPoints> shownPoints_;
  std::shared_ptr<const WarpVerdict> shownVerdict_;

  // GL
  unsigned program_ = 0, vao_ = 0, vbo_ = 0, refVao_ = 0, refVbo_ = 0;
  unsigned fbo_ = 0, colour_ = 0, depth_ = 0, panelTex_[3] = {0, 0, 0};
  int fboW_ = 0, fboH_ = 0;
  bool sceneDirty_ = true;  // the FBO is re-rendered only when the points, view or size change
  size_t pointCount_ = 0, lineVertexCount_ = 0, refVertexCount_ = 0;
  bool refSpherical_ = false;
  std::string refKey_;  // what the reference geometry was drawn for (inspectedName)
  bool refValid_ = false;

  // view
  glm::quat rot_{1.f, 0.f, 0.f, 0.f};  // arcball rotation
  float distance_ = 4.f;
  bool viewSpherical_ = false;
  bool viewInit_ = false;

  // layout of the panels in the last frame (screen pixels)
  float panelRect_[3][4] = {};
  double panelScale_ = 1.0;
};

// Standalone inspector (`penumbra warp --gui`): a window (or an OSMesa buffer) showing only it.
struct WarpGuiOptions {
  WarpInspectorSettings settings;
  int frames = 0;  // 0: until closed
  std::string screenshot;
  bool waitForResult = false;  // before the last frame, wait for the verdict of the settings
  bool printLayout = false;
  int windowWidth = 1280, windowHeight = 800;
};
int runWarpInspector(const WarpGuiOptions& options);

}  // namespace penumbra::ui
