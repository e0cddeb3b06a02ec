#include "core/render/render_job.h"

#include <gtest/gtest.h>

#include <memory>

#include "core/integrators/integrator_test_support.h"
#include "core/math/frame.h"
#include "core/render/engine.h"

namespace penumbra {
namespace {

RenderSettings withSampler(SamplerKind kind, uint32_t sceneCount) {
  RenderSettings s;
  s.samplerKind = kind;
  s.sampleCount = sceneCount;
  return s;
}

TEST(RenderJob, FitsACountShapedSamplerToTheRunsTargetSpp) {
  RenderJob s(nullptr, withSampler(SamplerKind::Stratified, 4), RenderLimits{64, 0.0});
  EXPECT_EQ(s.settings.sampleCount, 64u);
  EXPECT_EQ(s.samplerNote, "");
  RenderJob z(nullptr, withSampler(SamplerKind::ZSobol, 4), RenderLimits{50, 0.0});
  EXPECT_EQ(z.settings.sampleCount, 50u);
  EXPECT_EQ(z.samplerNote, samplerRow(SamplerKind::ZSobol).fitSampleCount(4, 50).note);
  EXPECT_NE(z.samplerNote.find("not a power of two"), std::string::npos) << z.samplerNote;
}

// A time limit alone leaves the final count unknown; with a target spp as well, the target is the
// count (the render stops there unless time runs out first).
TEST(RenderJob, ATimeLimitAloneKeepsTheScenesCountAndSaysSo) {
  RenderJob timed(nullptr, withSampler(SamplerKind::Stratified, 16), RenderLimits{0, 2.0});
  EXPECT_EQ(timed.settings.sampleCount, 16u);
  EXPECT_NE(timed.samplerNote.find("final sample count is not known"), std::string::npos)
      << timed.samplerNote;
  RenderJob endless(nullptr, withSampler(SamplerKind::ZSobol, 16), RenderLimits{});
  EXPECT_EQ(endless.settings.sampleCount, 16u);
  EXPECT_NE(endless.samplerNote.find("final sample count is not known"), std::string::npos);
  RenderJob both(nullptr, withSampler(SamplerKind::Stratified, 16), RenderLimits{36, 2.0});
  EXPECT_EQ(both.settings.sampleCount, 36u);
  EXPECT_EQ(both.samplerNote, "");
}

TEST(RenderJob, LeavesSamplersWithoutARuleAlone) {
  for (SamplerKind kind : {SamplerKind::Independent, SamplerKind::Sobol})
    for (RenderLimits limits : {RenderLimits{64, 0.0}, RenderLimits{0, 1.0}, RenderLimits{}}) {
      RenderJob job(nullptr, withSampler(kind, 4), limits);
      EXPECT_EQ(job.settings.sampleCount, 4u) << samplerKindName(kind);
      EXPECT_EQ(job.samplerNote, "") << samplerKindName(kind);
    }
}

TEST(RenderJob, KeepsTheRestOfTheSettingsAndTheOutput) {
  RenderSettings s = withSampler(SamplerKind::Stratified, 4);
  s.seed = 99;
  s.camera.width = 17;
  s.integrator = withCountsOf(directByLight(LightMeasure::Area), s.integrator);
  RenderJob job(nullptr, s, RenderLimits{9, 0.0}, RenderOutput::MisLightShare);
  s.sampleCount = 9;
  EXPECT_EQ(job.settings.seed, s.seed);
  EXPECT_EQ(job.settings.camera, s.camera);
  EXPECT_EQ(job.settings.integrator, s.integrator);
  EXPECT_EQ(job.settings.sampleCount, 9u);
  EXPECT_EQ(job.output, RenderOutput::MisLightShare);
}

// A plane under a sphere light, seen from above: light sampling draws 2-D points, so the strata
// show in the image.
std::shared_ptr<const Scene> litPlane() {
  std::shared_ptr<Scene> scene = test::planeScene();
  test::addSphere(*scene, Vec3(0.5f, 0.f, 2.f), 0.75f, Color3(10.f));
  test::finish(*scene);
  return scene;
}

RenderSettings lookingDown(SamplerKind kind, uint32_t sceneCount) {
  RenderSettings s = withSampler(kind, sceneCount);
  const Vec3 origin(0.f, 0.f, 6.f), dir(0.f, 0.f, -1.f), left(-1.f, 0.f, 0.f);
  s.camera.toWorld = cameraToWorld(origin, left, glm::cross(dir, left), dir);
  s.camera.width = 24;
  s.camera.height = 16;
  s.seed = 3;
  return s;
}

Image render(std::shared_ptr<const RenderJob> job, const RenderLimits& limits) {
  Engine engine;
  engine.start(std::move(job), limits, 2);
  engine.wait();
  return engine.film().mean(limits.targetSpp);
}

// Making the job is all it takes: the engine renders the fitted count. A job made for 16 spp from a
// scene count of 4 renders the image of 16 strata, not that of 4.
TEST(RenderJob, TheEngineRendersTheCountTheJobWasFittedTo) {
  const std::shared_ptr<const Scene> scene = litPlane();
  const RenderLimits limits{16, 0.0};
  for (SamplerKind kind : {SamplerKind::Stratified, SamplerKind::ZSobol}) {
    const Image fitted =
        render(std::make_shared<const RenderJob>(scene, lookingDown(kind, 4), limits), limits);
    // The same settings with the counts given directly: a job for an unknown count keeps them.
    const Image at16 =
        render(std::make_shared<const RenderJob>(scene, lookingDown(kind, 16), RenderLimits{}), limits);
    const Image at4 =
        render(std::make_shared<const RenderJob>(scene, lookingDown(kind, 4), RenderLimits{}), limits);
    EXPECT_EQ(fitted.rgb, at16.rgb) << samplerKindName(kind);  // bitwise
    EXPECT_NE(fitted.rgb, at4.rgb) << samplerKindName(kind);
  }
}

}  // namespace
}  // namespace penumbra
