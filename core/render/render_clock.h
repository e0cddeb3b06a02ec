// The clocks of one accumulation: rendering time with pauses excluded, and the process's CPU time,
// both counted from start().
#pragma once

#include <atomic>
#include <chrono>

namespace penumbra {

class RenderClock {
 public:
  // Zero now (wall and CPU time); the paused state carries over.
  void start();
  // Counts on from the reading stop() recorded (an accumulation extended after it stopped).
  void resume();
  // Pauses or resumes the clock; time paused while `counting` is excluded. False if nothing changed.
  bool setPaused(bool paused, bool counting);
  bool paused() const { return paused_.load(); }
  // Seconds since start(), pauses excluded (frozen while paused).
  double elapsed() const;
  // Records elapsed() as the accumulation's final time.
  void stop() { stoppedSeconds_ = elapsed(); }
  double stoppedSeconds() const { return stoppedSeconds_.load(); }
  // Process CPU time (all threads) since start().
  double cpuSeconds() const;

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_;
  Clock::time_point pauseBegan_;
  std::atomic<bool> paused_{false};
  std::atomic<double> pausedSeconds_{0.0};
  std::atomic<double> stoppedSeconds_{0.0};
  double cpuAtStart_ = 0.0;
};

}  // namespace penumbra
