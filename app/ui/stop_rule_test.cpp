// StopLimits and stopText: each rule remembers its value, the target follows the sampleCount while
// equal, and the text says what stops the render.
#include "app/ui/stop_rule.h"

#include <gtest/gtest.h>

using namespace penumbra;
using namespace penumbra::ui;

TEST(StopLimits, EachRuleRemembersItsValue) {
  StopLimits l;
  l.reset(64);
  EXPECT_EQ(l.rule(), StopRule::TargetSpp);
  EXPECT_EQ(l.limits().targetSpp, 64u);
  EXPECT_FALSE(l.chosenByUser(64));
  EXPECT_TRUE(l.set(l.withTimeBudget(3.0)));
  EXPECT_EQ(l.rule(), StopRule::TimeBudget);
  EXPECT_TRUE(l.chosenByUser(64));
  EXPECT_TRUE(l.set(l.forRule(StopRule::TargetSpp)));
  EXPECT_EQ(l.limits().targetSpp, 64u);
  EXPECT_EQ(l.limits().seconds, 0.0);
  EXPECT_TRUE(l.set(l.forRule(StopRule::TimeBudget)));
  EXPECT_EQ(l.limits().seconds, 3.0);
  EXPECT_FALSE(l.set(l.limits()));  // unchanged
  EXPECT_EQ(l.withTimeBudget(-1).seconds, StopLimits::kDefaultSeconds);
}

TEST(StopLimits, TheTargetFollowsTheSampleCountWhileEqual) {
  StopLimits l;
  l.reset(16);
  l.followSampleCount(16, 32);
  EXPECT_EQ(l.limits().targetSpp, 32u);
  EXPECT_EQ(l.chosenTargetSpp(), 32u);
  l.set(l.withTargetSpp(100));
  l.followSampleCount(32, 8);
  EXPECT_EQ(l.limits().targetSpp, 100u);
}

TEST(StopLimits, TheTextSaysWhatStops) {
  RenderLimits spp{64, 0.0, false}, endless{}, budget{0, 2.5, false}, equal{0, 10.0, false};
  EXPECT_EQ(stopText(spp, spp, false), "stops at 64 spp (target spp)");
  EXPECT_EQ(stopText(endless, endless, false), "renders until paused (target spp 0: endless)");
  EXPECT_EQ(stopText(budget, budget, false), "stops after 2.5 s (time budget)");
  EXPECT_EQ(stopText(budget, budget, true), "stops after 2.5 s (time budget, both sides)");
  EXPECT_EQ(stopText(equal, spp, true), "stops after 10.0 s (compare: equal time, both sides)");
}
