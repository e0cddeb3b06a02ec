// A program in the user's seat (the monkey test, the widget-ID audit): before every frame it sets
// ImGui's input and may switch the viewer's mode; after the frame it checks what the frame left.
// `penumbra view --monkey` and `--audit-ids` run the viewer under one (ViewerOptions::driver).
#pragma once

#include <string>

#include "app/ui/viewer_controller.h"

namespace penumbra::ui {

// What a driver may reach of the running viewer besides ImGui's input.
class DrivenViewer {
 public:
  virtual ViewerController& controller() = 0;
  virtual void setWarpInspectorOpen(bool open) = 0;
  virtual bool warpInspectorOpen() const = 0;
  virtual void setHelpOpen(bool open) = 0;
  // The window (framebuffer) size in pixels.
  virtual void windowSize(int& width, int& height) const = 0;
  // Where the last frame's time went ("snapshot poll 2 ms, panels 5, ..."), for reports.
  virtual std::string lastFrameBreakdown() const = 0;

 protected:
  ~DrivenViewer() = default;
};

class FrameDriver {
 public:
  virtual ~FrameDriver() = default;
  // Before frame `index` (0, 1, ...): sets ImGui's input for it. False ends the run.
  virtual bool beforeFrame(int index, DrivenViewer& viewer) = 0;
  // After it; `seconds`: the frame's wall time (snapshot poll, panels, display) less the time the UI
  // thread spent loading scenes and the time it and the GL rasteriser waited for a CPU
  // (run_queue_wait.h). False ends the run (a check failed).
  virtual bool afterFrame(int index, DrivenViewer& viewer, double seconds) = 0;
  // The frame threw: the UI reports errors in its panels, so an exception reaching the loop is a bug.
  virtual void frameThrew(int index, const std::string& what) = 0;
  // The process exit code of the run: 0 when every check passed.
  virtual int exitCode() const = 0;
};

}  // namespace penumbra::ui
