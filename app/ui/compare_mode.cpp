#include "app/ui/compare_mode.h"

#include <algorithm>
#include <thread>

#include "app/ui/strategy_choices.h"
#include "core/render/strategy_axes.h"

namespace penumbra::ui {

CompareMode::CompareMode(int threads, std::shared_ptr<PublishSignal> signal)
    : threads_(threads), left_(signal), right_(signal) {}

void CompareMode::setEnabled(bool on) {
  if (on == enabled_) return;
  enabled_ = on;
  if (!on) {
    right_.cancel();
    right_.clearSnapshot();
  }
}

int CompareMode::engineThreads() const {
  if (!enabled_) return threads_;
  int all = threads_ > 0 ? threads_ : int(std::max(1u, std::thread::hardware_concurrency()));
  return std::max(1, all / 2);
}

RenderLimits CompareMode::effectiveLimits(const RenderLimits& chosen) const {
  RenderLimits l = chosen;
  if (enabled_ && !(l.seconds > 0)) {
    l.targetSpp = 0;
    l.seconds = kSeconds;
  }
  return l;
}

std::string CompareMode::startLeft(SessionJob job, const RenderLimits& chosen) {
  return left_.start(std::move(job), effectiveLimits(chosen), engineThreads(), left_.paused());
}

void CompareMode::startRight(SessionJob job, const RenderLimits& chosen) {
  job.settings.integrator =
      renderedIntegrator(job.settings.integrator, job.scene && job.scene->hasAreaLights());
  right_.start(std::move(job), effectiveLimits(chosen), engineThreads(), left_.paused());
  right_.clearSnapshot();
}

void CompareMode::setPaused(bool paused) {
  left_.setPaused(paused);
  if (enabled_) right_.setPaused(paused);
}

bool CompareMode::busy() const {
  return left_.busy() || (enabled_ && right_.busy());
}

bool CompareMode::poll(bool wantStandardError, bool requestNext) {
  bool changed = left_.poll(wantStandardError, requestNext);
  if (enabled_ && right_.poll(wantStandardError, requestNext)) changed = true;
  return changed;
}

bool CompareMode::setIntegrator(const IntegratorDesc& d) {
  userChosen_ = true;
  if (d == integrator_) return false;
  integrator_ = d;
  return true;
}

void CompareMode::chooseDefault(const IntegratorDesc& left, bool sceneHasAreaLights) {
  if (!offersCompare(left)) return;
  const bool valid = comparable(integrator_, left, sceneHasAreaLights);
  if (valid && !(withCountsOf(integrator_, left) == left)) return;
  if (valid && userChosen_) return;
  integrator_ = defaultCompareStrategy(left, sceneHasAreaLights);
}

IntegratorDesc CompareMode::renderedIntegrator(const IntegratorDesc& left, bool sceneHasAreaLights) const {
  return applicableStrategy(withCountsOf(integrator_, left), sceneHasAreaLights);
}

}  // namespace penumbra::ui
