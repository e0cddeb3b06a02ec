// When the viewer's accumulation stops: at the target spp or after the time budget (the Sampler
// panel's choice). Each rule remembers its value, so switching to the other rule and back brings it
// back; the target spp follows the sampler's sampleCount while the two are equal.
#pragma once

#include <cstdint>
#include <string>

#include "core/render/render_job.h"

namespace penumbra::ui {

enum class StopRule { TargetSpp, TimeBudget };

class StopLimits {
 public:
  static constexpr double kDefaultSeconds = 10.0;

  // A new scene's: stop at its sampleCount; the time budget kDefaultSeconds.
  void reset(uint32_t sampleCount);
  const RenderLimits& limits() const { return limits_; }
  StopRule rule() const { return limits_.seconds > 0 ? StopRule::TimeBudget : StopRule::TargetSpp; }
  // Takes `l` and remembers its value for its rule; returns whether the limits changed.
  bool set(const RenderLimits& l);
  // The limits of each rule with the value it remembers, or with a new one (a budget <= 0 is
  // kDefaultSeconds; a target of 0 never stops).
  RenderLimits forRule(StopRule rule) const;
  RenderLimits withTargetSpp(uint32_t spp) const;
  RenderLimits withTimeBudget(double seconds) const;
  uint32_t chosenTargetSpp() const { return chosenTargetSpp_; }
  double chosenSeconds() const { return chosenSeconds_; }
  // The sampler's sampleCount changed: the target spp (running, and remembered) follows it while
  // they were equal (the stratified sampler's strata and the accumulation's end stay tied).
  void followSampleCount(uint32_t from, uint32_t to);
  // Whether the user chose limits other than the scene's (a reload keeps them then).
  bool chosenByUser(uint32_t sceneSampleCount) const;

 private:
  RenderLimits limits_;
  uint32_t chosenTargetSpp_ = 0;            // the target spp while the time budget rules
  double chosenSeconds_ = kDefaultSeconds;  // the time budget while the target spp rules
};

// What stops the render, e.g. "stops at 64 spp (target spp)" or "stops after 10.0 s (time budget,
// equal time)": `run` are the limits the engines run with, `chosen` the user's, `compare` whether
// compare mode is on.
std::string stopText(const RenderLimits& run, const RenderLimits& chosen, bool compare);

}  // namespace penumbra::ui
