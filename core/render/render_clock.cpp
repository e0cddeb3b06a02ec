#include "core/render/render_clock.h"

#include "core/render/cpu_clock.h"

namespace penumbra {

void RenderClock::start() {
  pausedSeconds_ = 0.0;
  stoppedSeconds_ = 0.0;
  start_ = Clock::now();
  cpuAtStart_ = processCpuSeconds();
  pauseBegan_ = start_;
}

void RenderClock::resume() {
  start_ = Clock::now() -
           std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(stoppedSeconds_.load()));
  pausedSeconds_ = 0.0;
}

bool RenderClock::setPaused(bool paused, bool counting) {
  if (paused == paused_.load()) return false;
  const auto now = Clock::now();
  if (paused)
    pauseBegan_ = now;
  else if (counting)
    pausedSeconds_ = pausedSeconds_ + std::chrono::duration<double>(now - pauseBegan_).count();
  paused_ = paused;
  return true;
}

double RenderClock::elapsed() const {
  const auto now = paused_ ? pauseBegan_ : Clock::now();
  return std::chrono::duration<double>(now - start_).count() - pausedSeconds_;
}

double RenderClock::cpuSeconds() const {
  return processCpuSeconds() - cpuAtStart_;
}

}  // namespace penumbra
