#include "app/ui/engine_session.h"

#include <utility>

namespace penumbra::ui {

EngineSession::EngineSession(std::shared_ptr<PublishSignal> signal) {
  engine_.setWorkerNice(kViewerWorkerNice);
  engine_.setPublishSignal(std::move(signal));
}

std::string EngineSession::start(SessionJob job, RenderLimits limits, int threads, bool paused) {
  RenderLimits fit = limits;
  if (limits.seconds > 0) fit.targetSpp = 0;  // a time budget: the final count is not known
  auto rendered =
      std::make_shared<const RenderJob>(std::move(job.scene), std::move(job.settings), fit, job.output);
  std::string note = rendered->samplerNote;
  limits.preview = true;  // a coarse first frame within milliseconds of any change
  output_ = rendered->output;
  engine_.start(std::move(rendered), limits, threads);
  if (paused) engine_.setPaused(true);
  ++restarts_;
  startTime_ = std::chrono::steady_clock::now();
  return note;
}

double EngineSession::secondsSinceStart() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - startTime_).count();
}

void EngineSession::setProbePixel(int x, int y) {
  probeX_ = x, probeY_ = y;
  engine_.setProbePixel(x, y);
}

bool EngineSession::poll(bool wantStandardError, bool requestNext) {
  // Once a pass is done, the pass after the running one is resolved by the workers as they render it
  // (no worker waits for a serial resolve at a boundary); the first pass is wanted at once.
  if (requestNext) {
    if (engine_.progress().spp >= 1)
      engine_.requestNextPassSnapshot(wantStandardError);
    else
      engine_.requestSnapshot(wantStandardError);
  }
  // Paused where no snapshot was requested: publish the pass the film holds.
  if (engine_.paused()) engine_.publishAtRest();
  bool changed = engine_.takeSnapshot(snapshot_);  // the session is its engine's only reader
  // The engine publishes only at pass boundaries where a snapshot was requested, so the final pass of
  // a finished accumulation may not have been published: read it from the (now idle) film.
  RenderProgress p = engine_.progress();
  bool needError = wantStandardError && snapshot_.standardError.empty() && p.spp >= 2;
  if (p.finished && p.spp > 0 && (snapshot_.spp != p.spp || needError || snapshot_.mean.empty())) {
    engine_.wait();
    snapshot_.mean = engine_.film().mean(p.spp);
    snapshot_.standardError = wantStandardError ? engine_.film().standardError(p.spp) : Image();
    snapshot_.spp = p.spp;
    snapshot_.seconds = p.seconds;
    changed = true;
  }
  // A resting film (paused, finished) publishes no more passes: read the hovered pixel directly.
  if (probeX_ >= 0 && (snapshot_.probe.x != probeX_ || snapshot_.probe.y != probeY_ || changed) &&
      !snapshot_.mean.empty()) {
    FilmSnapshot::Probe probe;
    if (engine_.probeAtRest(probeX_, probeY_, probe) && engine_.progress().spp == snapshot_.spp)
      snapshot_.probe = probe;
  }
  if (changed) snapshotRestart_ = restarts_, snapshotOutput_ = output_, ++snapshotSerial_;
  return changed;
}

}  // namespace penumbra::ui
