// The monkey test's run (`penumbra view --monkey SEED --frames N`, docs/viewer.md "Robustness"): the
// frames are split into four phases that start in the plain view, compare mode, the warp inspector
// and the MIS light-share view, and the monkey (app/ui/monkey.h) plays the user throughout. After
// every frame it fails the run on two widgets of one window sharing an ID, a frame slower than the
// limit, NaN/Inf in the displayed image or in the viewer's numbers, or an exception; an ImGui assert
// or a crash aborts the process, which prints the frame, the seed, the last inputs and the command
// that replays the run.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "app/ui/frame_driver.h"

namespace penumbra::ui {

struct MonkeyOptions {
  std::uint64_t seed = 1;
  int frames = -1;                 // -1: a replayed log's own count, else 1000
  double frameLimitSeconds = 1.0;  // the longest a frame may take (scene loading excluded)
  std::string logPath;             // every frame's input, one line each (formatInput)
  std::string replayPath;          // play back this log instead of the seeded monkey
  std::string openScene;           // opened at frame 0 as from the Scene panel (e.g. a scene with errors)
  std::string replayCommand;       // printed on failure: the command line that runs this again
};

std::shared_ptr<FrameDriver> makeMonkeyDriver(const MonkeyOptions& options);

}  // namespace penumbra::ui
