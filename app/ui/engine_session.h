// One render of the viewer: an Engine, the newest snapshot taken from it, and its counters. A start
// begins a new accumulation (with the engine's preview, keeping a pause); polling takes the newest
// published pass, and reads a resting film (paused, finished) directly. The left side of the image
// and compare mode's right side are one each (compare_mode.h).
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "core/render/engine.h"

namespace penumbra::ui {

// Nice value of the render threads while the viewer runs (Engine::setWorkerNice): the UI thread and the
// GL rasteriser's threads preempt them for the few ms a frame takes, instead of getting a fair share.
inline constexpr int kViewerWorkerNice = 10;

// What a start renders, before the start's limits fit its sampler (the RenderJob is made from it).
struct SessionJob {
  std::shared_ptr<const Scene> scene;
  RenderSettings settings;
  RenderOutput output = RenderOutput::Radiance;
};

class EngineSession {
 public:
  // The engine notifies `signal` on every snapshot and when it stops (the UI sleeps on it).
  explicit EngineSession(std::shared_ptr<PublishSignal> signal);
  ~EngineSession() { engine_.cancel(); }

  // Starts a new accumulation of `job` within `limits` on `threads` (<= 0: all cores), paused when
  // `paused`. A count-shaped sampler (stratified, zsobol) is fitted to the target spp (none under a
  // time budget: the final count is then unknown); returns what that fit says (empty when the
  // pattern is simply the target's).
  std::string start(SessionJob job, RenderLimits limits, int threads, bool paused);
  // New limits for the running accumulation (Engine::extend); false when it must start again.
  bool extend(const RenderLimits& limits) { return engine_.extend(limits); }
  void cancel() { engine_.cancel(); }
  void setPaused(bool paused) { engine_.setPaused(paused); }
  bool paused() const { return engine_.paused(); }
  RenderProgress progress() const { return engine_.progress(); }
  // Accumulating: neither paused nor finished.
  bool busy() const { return !engine_.paused() && !engine_.progress().finished; }

  // Takes the newest published snapshot and, with requestNext, asks for another; true when
  // snapshot() changed.
  bool poll(bool wantStandardError, bool requestNext);
  // The pixel under the cursor (x < 0: none): snapshot().probe carries its statistics, from the next
  // published pass, or at once while the film rests.
  void setProbePixel(int x, int y);
  const FilmSnapshot& snapshot() const { return snapshot_; }
  void clearSnapshot() { snapshot_ = FilmSnapshot{}; }

  uint64_t restarts() const { return restarts_; }                // starts so far
  uint64_t snapshotRestart() const { return snapshotRestart_; }  // the start snapshot() came from
  uint64_t snapshotSerial() const { return snapshotSerial_; }    // changes of snapshot()
  RenderOutput snapshotOutput() const { return snapshotOutput_; }
  double secondsSinceStart() const;
  Engine& engine() { return engine_; }
  const Engine& engine() const { return engine_; }

 private:
  Engine engine_;
  FilmSnapshot snapshot_;
  int probeX_ = -1, probeY_ = -1;
  uint64_t restarts_ = 0, snapshotRestart_ = 0, snapshotSerial_ = 0;
  RenderOutput output_ = RenderOutput::Radiance;          // of the current job
  RenderOutput snapshotOutput_ = RenderOutput::Radiance;  // of the job snapshot_ came from
  std::chrono::steady_clock::time_point startTime_{};
};

}  // namespace penumbra::ui
