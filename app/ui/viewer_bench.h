// `penumbra view --bench`: the engine's throughput alone and beside the viewer's frame loop, restart
// latency, and where a frame's time goes. It drives the viewer through BenchViewer only.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>

#include "app/platform/platform.h"
#include "app/ui/image_display.h"
#include "app/ui/viewer_controller.h"

namespace penumbra::ui {

// Parts of a frame, timed separately by the bench's breakdown.
enum FrameStage { kUi, kTonemap, kImage, kPanels, kPresent, kFrameStages };

// Times the parts of frames: each part ends with glFinish, then adds its wall and process CPU time.
class FrameStageTimer {
 public:
  void begin();
  void end(FrameStage stage);
  std::array<double, kFrameStages> wallMs{}, cpuMs{};  // summed over frames

 private:
  std::chrono::steady_clock::time_point wall_{};
  double cpuMs_ = 0;
};

// The viewer as the bench drives it.
class BenchViewer {
 public:
  // The interactive loop until `done()`; `continuous` draws every (paced) frame, as while a slider
  // is dragged.
  virtual void run(const std::function<bool()>& done, bool continuous) = 0;
  // Draws and presents one frame now.
  virtual void frame() = 0;
  virtual uint64_t framesDrawn() const = 0;
  virtual double lastFrameMs() const = 0;
  // Restart count of the image the last frame showed (0: none).
  virtual uint64_t shownRestart() const = 0;
  virtual Tonemapper tonemapper() const = 0;
  // The next frame tone maps the image again, as a frame with a new snapshot does.
  virtual void forceTonemap() = 0;
  // Later frames time their parts into `timer` (nullptr: not timed).
  virtual void timeStages(FrameStageTimer* timer) = 0;

 protected:
  ~BenchViewer() = default;
};

// Prints the measurements; returns the process exit code.
int runViewerBench(platform::Platform& p, ViewerController& c, BenchViewer& viewer);

}  // namespace penumbra::ui
