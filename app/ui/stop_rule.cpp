#include "app/ui/stop_rule.h"

#include <cstdio>

namespace penumbra::ui {

void StopLimits::reset(uint32_t sampleCount) {
  limits_ = RenderLimits{};
  limits_.targetSpp = sampleCount;
  chosenTargetSpp_ = sampleCount;
  chosenSeconds_ = kDefaultSeconds;
}

bool StopLimits::set(const RenderLimits& l) {
  // Each rule remembers its value for when the user switches back to it.
  if (l.seconds > 0)
    chosenSeconds_ = l.seconds;
  else
    chosenTargetSpp_ = l.targetSpp;
  if (l.targetSpp == limits_.targetSpp && l.seconds == limits_.seconds) return false;
  limits_ = l;
  return true;
}

RenderLimits StopLimits::forRule(StopRule rule) const {
  return rule == StopRule::TimeBudget ? withTimeBudget(chosenSeconds_) : withTargetSpp(chosenTargetSpp_);
}

RenderLimits StopLimits::withTargetSpp(uint32_t spp) const {
  RenderLimits l = limits_;
  l.targetSpp = spp;
  l.seconds = 0;
  return l;
}

RenderLimits StopLimits::withTimeBudget(double seconds) const {
  RenderLimits l = limits_;
  l.targetSpp = 0;
  l.seconds = seconds > 0 ? seconds : kDefaultSeconds;
  return l;
}

void StopLimits::followSampleCount(uint32_t from, uint32_t to) {
  if (to == from) return;
  if (limits_.seconds <= 0 && limits_.targetSpp == from) limits_.targetSpp = to;
  if (chosenTargetSpp_ == from) chosenTargetSpp_ = to;
}

bool StopLimits::chosenByUser(uint32_t sceneSampleCount) const {
  return limits_.seconds > 0 || limits_.targetSpp != sceneSampleCount;
}

std::string stopText(const RenderLimits& run, const RenderLimits& chosen, bool compare) {
  char buf[160];
  if (run.seconds > 0)
    std::snprintf(buf, sizeof buf, "stops after %.1f s (%s)", run.seconds,
                  compare
                      ? (chosen.seconds > 0 ? "time budget, both sides" : "compare: equal time, both sides")
                      : "time budget");
  else if (run.targetSpp > 0)
    std::snprintf(buf, sizeof buf, "stops at %u spp (target spp)", run.targetSpp);
  else
    std::snprintf(buf, sizeof buf, "renders until paused (target spp 0: endless)");
  return buf;
}

}  // namespace penumbra::ui
