// Compare mode: two EngineSessions at equal time. The left side renders the live settings; while
// compare mode is on, the right side renders the same scene, camera and sampler with its own strategy
// (one of the left integrator type's, with its counts; strategy_choices.h), each engine on half of the
// threads (at least one), and unless the user chose a time budget both stop after kSeconds instead of at an
// spp count, so both strategies get equal shares of time.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/ui/engine_session.h"

namespace penumbra::ui {

class CompareMode {
 public:
  // Both sides' render time in compare mode when the user chose no time budget.
  static constexpr double kSeconds = 10.0;

  // `threads` <= 0: all cores, shared by the two sides while compare mode is on.
  CompareMode(int threads, std::shared_ptr<PublishSignal> signal);

  EngineSession& left() { return left_; }
  const EngineSession& left() const { return left_; }
  EngineSession& right() { return right_; }
  const EngineSession& right() const { return right_; }

  bool enabled() const { return enabled_; }
  // Turns compare mode on or off; off cancels the right side and drops its image. Starts nothing: both
  // sides then start together with their new share of the threads.
  void setEnabled(bool on);
  // Threads per engine in the current mode.
  int engineThreads() const;
  // The limits the engines run with: `chosen`, or the shared time budget in compare mode.
  RenderLimits effectiveLimits(const RenderLimits& chosen) const;

  // Starts the left side with `job`; returns its sampler note (EngineSession::start). The right side
  // keeps its accumulation.
  std::string startLeft(SessionJob job, const RenderLimits& chosen);
  // Starts the right side: `job` with renderedIntegrator() in place of its integrator; its old image is
  // dropped. Both sides start paused while the left one is.
  void startRight(SessionJob job, const RenderLimits& chosen);
  void setPaused(bool paused);
  // Accumulating on either side (the right one only while compare mode is on).
  bool busy() const;
  // Polls the left side, and the right one while compare mode is on; true when either image changed.
  bool poll(bool wantStandardError, bool requestNext);

  // ---- the right side's strategy -----------------------------------------------------------------
  const IntegratorDesc& integrator() const { return integrator_; }
  // The user's choice; kept while it applies. Returns whether it changed.
  bool setIntegrator(const IntegratorDesc& d);
  // Keeps the right side's strategy one of left's type that the scene can render and that differs
  // from `left` when another applies; the user's choice stays while it is comparable.
  void chooseDefault(const IntegratorDesc& left, bool sceneHasAreaLights);
  // What the right side renders: integrator() with the left side's counts, or its fallback when the
  // scene lacks what it needs.
  IntegratorDesc renderedIntegrator(const IntegratorDesc& left, bool sceneHasAreaLights) const;

 private:
  int threads_;
  bool enabled_ = false;
  IntegratorDesc integrator_;
  bool userChosen_ = false;  // setIntegrator was called: keep it while it applies
  EngineSession left_, right_;
};

}  // namespace penumbra::ui
