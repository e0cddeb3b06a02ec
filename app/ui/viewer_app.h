// The interactive viewer: a Platform (GLFW window or OSMesa buffer), the ViewerController (engine,
// scene, live settings), the GL image display and the ImGui panels, and the frame loop that ties
// them together. Also the offscreen screenshot mode; --bench runs app/ui/viewer_bench.h on it.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "app/ui/frame_driver.h"
#include "app/ui/viewer_controller.h"

namespace penumbra::ui {

struct ViewerOptions {
  double loadSeconds = 0;  // how long loading the scene took (shown in the Scene panel)
  int frames = 0;          // stop after this many frames (0: until the window closes)
  std::string screenshot;  // write the final frame (UI included) here as PNG
  bool bench = false;
  bool waitForTarget = false;  // before the screenshot, wait until the accumulation reaches its limit
  int windowWidth = 0, windowHeight = 0;  // 0: fit the image beside the panels
  int threads = 0;
  std::string compare;             // non-empty: start in compare mode with this strategy on the right
  bool openWarpInspector = false;  // start with the warp inspector window open (screenshots)
  bool printLayout = false;     // print "image-rect X Y W H ZOOM", "sidebar W", "section NAME Y", ... (tests)
  bool lightShareView = false;  // start in the "MIS light share" view (a mis strategy, no compare)
  std::string reference;        // non-empty: load this EXR/PFM as the Convergence panel's reference
  // After every snapshot poll (last = false) and once when the viewer closes (last = true).
  std::function<void(const ViewerController&, bool last)> onSnapshot;
  // Runs the viewer under this driver's input and checks instead of a person's (--monkey, --audit-ids).
  std::shared_ptr<FrameDriver> driver;
};

// Width of the panel column on the left in a 1280-pixel window, for sizing the default window (the
// column follows the window's width: app/ui/panel_layout.h).
constexpr int kSidebarWidth = 400;

// Runs the viewer on the current platform build. Returns the process exit code.
int runViewer(LoadedScene scene, ViewerController::Overrides overrides, const ViewerOptions& options);

}  // namespace penumbra::ui
