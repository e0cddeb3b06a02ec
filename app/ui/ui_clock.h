// The wall clock of the viewer's frame loop and of its bench.
#pragma once

#include <chrono>

namespace penumbra::ui {

using Clock = std::chrono::steady_clock;

// Milliseconds since t0.
inline double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

}  // namespace penumbra::ui
