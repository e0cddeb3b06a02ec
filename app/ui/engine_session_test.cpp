// EngineSession and CompareMode without the viewer: a start is a new accumulation whose snapshots
// arrive by polling, a pause survives a start, a resting film is read directly, and compare mode
// splits the threads and runs both sides for the same time.
#include "app/ui/compare_mode.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "app/ui/engine_session.h"
#include "app/ui/wait_until_test_support.h"
#include "core/scene/scene_builder.h"

using namespace penumbra;
using namespace penumbra::ui;

namespace {

SessionJob smallJob() {
  LoadedScene s = loadSceneFromString(defaultSceneXml(), "built-in", ".",
                                      {{"camera.width", "24"}, {"camera.height", "16"}});
  return SessionJob{s.scene, s.settings, RenderOutput::Radiance};
}

using test::waitUntil;

}  // namespace

TEST(EngineSession, PollsTheSnapshotsOfEachStart) {
  EngineSession s(std::make_shared<PublishSignal>());
  EXPECT_EQ(s.restarts(), 0u);
  RenderLimits limits;
  limits.targetSpp = 4;
  EXPECT_EQ(s.start(smallJob(), limits, 1, false), "");
  EXPECT_EQ(s.restarts(), 1u);
  ASSERT_TRUE(waitUntil([&] {
    s.poll(false, true);
    return s.snapshot().spp == 4;
  }));
  EXPECT_EQ(s.snapshotRestart(), 1u);
  EXPECT_GE(s.snapshotSerial(), 1u);
  EXPECT_FALSE(s.busy());  // finished
  // The finished film is read directly, with its standard error when asked.
  ASSERT_TRUE(s.poll(true, false));
  EXPECT_FALSE(s.snapshot().standardError.empty());

  // A paused session starts paused; the probe is read from the resting film.
  s.setPaused(true);
  limits.targetSpp = 0;
  s.start(smallJob(), limits, 1, s.paused());
  EXPECT_TRUE(s.paused());
  EXPECT_FALSE(s.busy());
  EXPECT_EQ(s.restarts(), 2u);
  s.setPaused(false);
  ASSERT_TRUE(waitUntil([&] { return s.progress().spp >= 2; }));
  s.setPaused(true);
  s.setProbePixel(3, 2);
  ASSERT_TRUE(waitUntil([&] {
    s.poll(false, true);
    return s.snapshot().probe.x == 3 && s.snapshotRestart() == 2;
  }));
  EXPECT_EQ(s.snapshot().probe.mean, s.snapshot().mean.at(3, 2));
  s.clearSnapshot();
  EXPECT_TRUE(s.snapshot().mean.empty());
}

TEST(CompareMode, SplitsTheThreadsAndRendersBothSidesForTheSameTime) {
  CompareMode c(4, std::make_shared<PublishSignal>());
  RenderLimits chosen;
  chosen.targetSpp = 64;
  EXPECT_EQ(c.engineThreads(), 4);
  EXPECT_EQ(c.effectiveLimits(chosen).targetSpp, 64u);
  c.setEnabled(true);
  EXPECT_EQ(c.engineThreads(), 2);
  EXPECT_EQ(c.effectiveLimits(chosen).targetSpp, 0u);
  EXPECT_EQ(c.effectiveLimits(chosen).seconds, CompareMode::kSeconds);
  chosen.seconds = 2.0;  // the user's time budget is both sides'
  EXPECT_EQ(c.effectiveLimits(chosen).seconds, 2.0);

  // The right side renders its own strategy, falling back where the scene lacks what it needs.
  const IntegratorDesc left = directByLight(LightMeasure::SolidAngle);
  c.chooseDefault(left, true);
  EXPECT_EQ(strategyLabel(c.integrator()), strategyLabel(directByHemisphere(HemisphereWarp::Uniform)));
  EXPECT_TRUE(c.setIntegrator(withSamples(directByMis(LightMeasure::SolidAngle, MisHeuristic::Power), 1)));
  EXPECT_FALSE(c.setIntegrator(withSamples(directByMis(LightMeasure::SolidAngle, MisHeuristic::Power), 1)));
  EXPECT_NE(strategyLabel(c.renderedIntegrator(left, false)),
            strategyLabel(directByMis(LightMeasure::SolidAngle, MisHeuristic::Power)));
  // The right side renders with the left side's counts.
  EXPECT_EQ(c.renderedIntegrator(withSamples(left, 7), true).samples, 7);
  c.startLeft(smallJob(), chosen);
  c.startRight(smallJob(), chosen);
  ASSERT_TRUE(c.right().engine().job());
  EXPECT_EQ(strategyLabel(c.right().engine().job()->settings.integrator),
            strategyLabel(directByMis(LightMeasure::SolidAngle, MisHeuristic::Power)));
  EXPECT_EQ(c.left().engine().threadCount(), 2);
  ASSERT_TRUE(waitUntil([&] {
    c.poll(false, true);
    return c.left().snapshot().spp >= 1 && c.right().snapshot().spp >= 1;
  }));
  c.setPaused(true);
  EXPECT_TRUE(c.right().paused());
  EXPECT_FALSE(c.busy());
  // Off: the right side stops and its image goes.
  c.setEnabled(false);
  EXPECT_TRUE(c.right().snapshot().mean.empty());
  EXPECT_EQ(c.engineThreads(), 4);
}
