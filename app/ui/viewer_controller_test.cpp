// ViewerController: the viewer's state without GL, driven through its API: which changes restart the
// accumulation, the probe pixel, camera and sampler edits, the live scene XML, scene errors, and the
// side-by-side compare mode.
#include "app/ui/viewer_controller.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "app/ui/light_share_map.h"
#include "app/ui/wait_until_test_support.h"
#include "core/image/image_io.h"
#include "core/image/tonemap.h"
#include "core/integrators/mis_light_share.h"
#include "core/scene/light_selection_default.h"
#include "core/scene/scaling_scene.h"
#include "core/scene/scene_builder.h"

namespace fs = std::filesystem;
using namespace penumbra;

namespace {

LoadedScene smallDefaultScene() {
  return loadSceneFromString(
      defaultSceneXml(), "<built-in scene>", ".",
      {{"camera.width", "48"}, {"camera.height", "32"}, {"sampler.sampleCount", "100000"}});
}

void waitForSpp(ui::ViewerController& c, uint32_t spp) {
  auto t0 = std::chrono::steady_clock::now();
  while (c.progress().spp < spp && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(30))
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
}

using test::waitUntil;

// Picks direct's measure `name` as the Integrator panel does: that axis alone changes.
void pickMeasure(ui::ViewerController& c, std::string_view name) {
  RenderSettings s = c.settings();
  ASSERT_TRUE(applyMeasure(name, s.integrator)) << name;
  c.setSettings(s);
}

}  // namespace

TEST(ViewerController, MeasureChangeRestartsAccumulationExposureDoesNot) {
  ui::ViewerController c(smallDefaultScene(), {}, 2);
  c.start();
  waitForSpp(c, 3);
  uint64_t restarts = c.restartCount();
  uint32_t before = c.progress().spp;
  ASSERT_GE(before, 3u);

  // Display-only changes: no restart, the spp counter keeps growing.
  c.display.exposure += 2.f;
  c.display.tonemap = ui::Tonemap::Gamma22;
  c.display.falseColour = ui::FalseColour::RelativeError;
  c.display.zoom = 2.f;
  c.pollSnapshot(true);
  EXPECT_EQ(c.restartCount(), restarts);
  waitForSpp(c, before + 2);
  EXPECT_GE(c.progress().spp, before + 2);

  // Same settings again: nothing to restart.
  c.setSettings(c.settings());
  EXPECT_EQ(c.restartCount(), restarts);

  // A change of measure: restart, the counter resets.
  uint32_t running = c.progress().spp;
  RenderSettings s = c.settings();
  ASSERT_EQ(strategyLabel(s.integrator), strategyLabel(directByLight(LightMeasure::SolidAngle)));
  s.integrator = withCountsOf(directByLight(LightMeasure::Area), s.integrator);
  c.setSettings(s);
  EXPECT_EQ(c.restartCount(), restarts + 1);
  EXPECT_LT(c.progress().spp, running);
  EXPECT_EQ(strategyLabel(c.settings().integrator), strategyLabel(directByLight(LightMeasure::Area)));
  // The shared scene is reused, not rebuilt.
  EXPECT_EQ(c.engine().job()->scene.get(), c.scene().scene.get());
}

TEST(ViewerController, HoveredPixelStatisticsWithoutTheWholeImagesError) {
  ui::ViewerController c(smallDefaultScene(), {}, 2);
  c.setProbePixel(30, 20);
  c.start();
  // Snapshots come from passes after the probe was set; none of them resolves the whole error image.
  auto probed = [&] {
    c.pollSnapshot(false);
    return c.snapshot().probe.x == 30 && c.snapshot().spp >= 2;
  };
  auto t0 = std::chrono::steady_clock::now();
  while (!probed() && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(30))
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ASSERT_TRUE(probed());
  EXPECT_EQ(c.snapshot().probe.y, 20);
  EXPECT_EQ(c.snapshot().probe.mean, c.snapshot().mean.at(30, 20));
  EXPECT_TRUE(c.snapshot().standardError.empty());

  // Paused: the film rests at a pass boundary, so another pixel is read at once.
  c.setPaused(true);
  c.setProbePixel(5, 6);
  t0 = std::chrono::steady_clock::now();
  while (c.snapshot().probe.x != 5 && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(30)) {
    c.pollSnapshot(false);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  EXPECT_EQ(c.snapshot().probe.x, 5);
  EXPECT_EQ(c.snapshot().probe.y, 6);
  EXPECT_EQ(c.snapshot().probe.mean, c.snapshot().mean.at(5, 6));
  c.setPaused(false);
}

TEST(ViewerController, CameraAndSamplerChangesRestartAndLiveXmlRoundTrips) {
  ui::ViewerController c(smallDefaultScene(), {}, 1);
  c.start();
  uint64_t r0 = c.restartCount();
  glm::mat4 before = c.settings().camera.toWorld;
  c.orbit(40.f, 10.f);
  EXPECT_EQ(c.restartCount(), r0 + 1);
  EXPECT_NE(c.settings().camera.toWorld, before);
  c.dolly(2.f);
  c.pan(5.f, -3.f);
  EXPECT_EQ(c.restartCount(), r0 + 3);
  RenderSettings s = c.settings();
  s.seed = 17;
  s.samplerKind = SamplerKind::Stratified;
  s.integrator = withCountsOf(aoBy(HemisphereWarp::Uniform), s.integrator);
  s.integrator.samples = 3;
  c.setSettings(s);
  EXPECT_EQ(c.restartCount(), r0 + 4);

  // The live settings as scene XML parse back to the same settings.
  LoadedScene again = loadSceneFromString(c.liveSceneXml(), "live.xml", ".");
  const RenderSettings& t = again.settings;
  EXPECT_EQ(t.seed, 17u);
  EXPECT_EQ(t.samplerKind, SamplerKind::Stratified);
  EXPECT_EQ(strategyLabel(t.integrator), strategyLabel(aoBy(HemisphereWarp::Uniform)));
  EXPECT_EQ(t.integrator.samples, 3);
  EXPECT_EQ(t.camera.width, 48);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(t.camera.toWorld[i][j], c.settings().camera.toWorld[i][j], 1e-5f);

  c.resetCamera();
  EXPECT_EQ(c.settings().camera.toWorld, before);
}

// The target spp stratifies stratified and zsobol: a new target restarts them with that count;
// independent and sobol extend their accumulation; endless accumulation says what it does.
TEST(ViewerController, TargetSppSetsTheSampleCountOfCountShapedSamplers) {
  ui::ViewerController c(smallDefaultScene(), {}, 1);
  RenderSettings s = c.settings();
  s.samplerKind = SamplerKind::Sobol;
  c.setSettings(s);
  uint64_t r0 = c.restartCount();
  RenderLimits l = c.limits();
  l.targetSpp = 64;
  c.setLimits(l);
  EXPECT_EQ(c.restartCount(), r0);  // extended
  EXPECT_EQ(c.samplerNote(), "");

  s.samplerKind = SamplerKind::Stratified;
  c.setSettings(s);
  EXPECT_EQ(c.engine().job()->settings.sampleCount, 64u);
  uint64_t r1 = c.restartCount();
  l.targetSpp = 49;
  c.setLimits(l);
  EXPECT_EQ(c.restartCount(), r1 + 1);
  EXPECT_EQ(c.engine().job()->settings.sampleCount, 49u);
  EXPECT_EQ(c.samplerNote(), "");
  l.targetSpp = 0;  // endless
  c.setLimits(l);
  EXPECT_NE(c.samplerNote().find("final sample count is not known"), std::string::npos) << c.samplerNote();
  EXPECT_EQ(c.engine().job()->settings.sampleCount, 100000u);  // the scene's
}

TEST(ViewerController, InvalidSceneKeepsTheLastGoodOneAndShowsFileAndLine) {
  std::string bad =
      (fs::temp_directory_path() / ("penumbra-viewer-controller-" + std::to_string(::getpid()) + "-bad.xml"))
          .string();
  std::ofstream(bad)
      << "<scene>\n  <integrator type=\"direct\">\n    <integer name=\"nSamples\" value=\"x\"/>\n"
         "  </integrator>\n</scene>\n";
  ui::ViewerController c(smallDefaultScene(), {}, 1);
  c.start();
  auto scene = c.scene().scene;
  EXPECT_FALSE(c.openScene(bad));
  EXPECT_NE(c.sceneError().find("-bad.xml:3"), std::string::npos) << c.sceneError();
  EXPECT_EQ(c.scene().scene, scene);
  fs::remove(bad);
}

// The light-selection control: the selection switches the strategy live (a restart, the same shared
// scene), a measure change keeps it, and the saved XML names it.
TEST(ViewerController, LightSelectionSwitchesLiveAndAMeasureChangeKeepsIt) {
  const int many = int(kAllLightsUpTo) + 1;
  ui::ViewerController c(loadSceneFromString(scalingSceneXml(many, 16, 100000), "scaling.xml", "."), {}, 2);
  EXPECT_EQ(c.areaLightCount(), size_t(many));
  EXPECT_EQ(c.defaultLightSelection(), kManyLightsSelection);
  // The scene names no lightSelection: the builder resolved it by the light count.
  EXPECT_EQ(strategyLabel(c.settings().integrator),
            strategyLabel(directByLight(LightMeasure::SolidAngle, LightSelection::Bvh)));
  EXPECT_TRUE(c.settings().integrator.usesLightSelection());
  EXPECT_EQ(c.lightSelectionDefaultText(), "default for " + std::to_string(many) +
                                               " area lights: bvh (all up to " +
                                               std::to_string(kAllLightsUpTo) + ")");

  c.start();
  waitForSpp(c, 1);
  uint64_t r0 = c.restartCount();
  c.setLightSelection(LightSelection::Power);
  EXPECT_EQ(strategyLabel(c.settings().integrator),
            strategyLabel(directByLight(LightMeasure::SolidAngle, LightSelection::Power)));
  EXPECT_EQ(c.restartCount(), r0 + 1);
  EXPECT_EQ(strategyLabel(c.engine().job()->settings.integrator),
            strategyLabel(directByLight(LightMeasure::SolidAngle, LightSelection::Power)));
  EXPECT_EQ(c.engine().job()->scene.get(), c.scene().scene.get());
  c.setLightSelection(LightSelection::Power);  // unchanged: no restart
  EXPECT_EQ(c.restartCount(), r0 + 1);
  // Another measure keeps the selection.
  pickMeasure(c, "area");
  EXPECT_EQ(strategyLabel(c.settings().integrator),
            strategyLabel(directByLight(LightMeasure::Area, LightSelection::Power)));
  EXPECT_EQ(c.restartCount(), r0 + 2);
  // The saved XML names the selection the render used.
  LoadedScene saved = loadSceneFromString(c.liveSceneXml(), "live.xml", ".");
  EXPECT_EQ(strategyLabel(saved.settings.integrator),
            strategyLabel(directByLight(LightMeasure::Area, LightSelection::Power)));
  EXPECT_NE(c.liveSceneXml().find("name=\"lightSelection\" value=\"power\""), std::string::npos);
  // A measure without light selection: the control's setter does nothing, and MIS's XML names none.
  pickMeasure(c, "mis");
  EXPECT_FALSE(c.settings().integrator.usesLightSelection());
  EXPECT_EQ(c.liveSceneXml().find("lightSelection"), std::string::npos);
  pickMeasure(c, "hemisphere");
  uint64_t r1 = c.restartCount();
  c.setLightSelection(LightSelection::Uniform);
  EXPECT_EQ(strategyLabel(c.settings().integrator),
            strategyLabel(directByHemisphere(HemisphereWarp::Cosine)));
  EXPECT_EQ(c.restartCount(), r1);
  // Back to a light-sampling measure: the selection chosen before.
  pickMeasure(c, "solid-angle");
  EXPECT_EQ(strategyLabel(c.settings().integrator),
            strategyLabel(directByLight(LightMeasure::SolidAngle, LightSelection::Power)));
  // setStrategy sets every axis.
  c.setStrategy(directByLight(LightMeasure::Area));
  EXPECT_EQ(strategyLabel(c.settings().integrator), strategyLabel(directByLight(LightMeasure::Area)));
}

TEST(ViewerController, TheAssignmentSceneDefaultsToAllLights) {
  ui::ViewerController c(smallDefaultScene(), {}, 1);
  EXPECT_EQ(c.areaLightCount(), 1u);
  EXPECT_EQ(c.defaultLightSelection(), LightSelection::All);
  EXPECT_EQ(strategyLabel(c.settings().integrator), strategyLabel(directByLight(LightMeasure::SolidAngle)));
  EXPECT_EQ(c.lightSelectionDefaultText(),
            "default for 1 area light: all (all up to " + std::to_string(kAllLightsUpTo) + ")");
}

TEST(ViewerCompare, EnablingStartsASecondAccumulationDisablingStopsIt) {
  ui::ViewerController c(smallDefaultScene(), {}, 2);
  c.start();
  EXPECT_FALSE(c.compareEnabled());
  c.setCompareIntegrator(directByLight(LightMeasure::Area));  // compare off: nothing starts
  EXPECT_EQ(c.compareRestartCount(), 0u);
  EXPECT_EQ(c.compareProgress().spp, 0u);

  c.setCompare(true);
  EXPECT_TRUE(c.compareEnabled());
  EXPECT_EQ(c.compareRestartCount(), 1u);
  // Equal shares of the machine: one thread each out of two.
  EXPECT_EQ(c.engineThreads(), 1);
  EXPECT_EQ(c.engine().threadCount(), 1);
  EXPECT_EQ(c.compareEngine().threadCount(), 1);
  // Same scene object and settings, only the integrator differs.
  ASSERT_TRUE(c.compareEngine().job());
  EXPECT_EQ(c.compareEngine().job()->scene.get(), c.scene().scene.get());
  EXPECT_EQ(strategyLabel(c.compareEngine().job()->settings.integrator),
            strategyLabel(directByLight(LightMeasure::Area)));
  EXPECT_EQ(strategyLabel(c.engine().job()->settings.integrator),
            strategyLabel(directByLight(LightMeasure::SolidAngle)));
  EXPECT_EQ(c.compareEngine().job()->settings.camera.toWorld, c.settings().camera.toWorld);

  // Both spp counters grow; both snapshots are published.
  ASSERT_TRUE(waitUntil([&] { return c.progress().spp >= 3 && c.compareProgress().spp >= 3; }));
  uint32_t a = c.progress().spp, b = c.compareProgress().spp;
  ASSERT_TRUE(waitUntil([&] { return c.progress().spp >= a + 2 && c.compareProgress().spp >= b + 2; }));
  ASSERT_TRUE(waitUntil([&] {
    c.pollSnapshot(false);
    return c.snapshot().spp >= 1 && c.compareSnapshot().spp >= 1;
  }));
  EXPECT_EQ(c.compareSnapshot().mean.width, c.snapshot().mean.width);
  EXPECT_EQ(c.compareSnapshot().mean.height, c.snapshot().mean.height);

  // Disabling stops the second accumulation; the left one goes back to all threads.
  uint64_t leftRestarts = c.restartCount();
  c.setCompare(false);
  EXPECT_FALSE(c.compareEnabled());
  EXPECT_TRUE(c.compareProgress().finished);
  uint32_t stopped = c.compareProgress().spp;
  EXPECT_EQ(c.restartCount(), leftRestarts + 1);
  EXPECT_EQ(c.engine().threadCount(), 2);
  ASSERT_TRUE(waitUntil([&] { return c.progress().spp >= 3; }));
  EXPECT_EQ(c.compareProgress().spp, stopped);
  EXPECT_TRUE(c.compareSnapshot().mean.empty());
}

TEST(ViewerCompare, ChangingOneSidesStrategyRestartsOnlyThatSide) {
  ui::ViewerController c(smallDefaultScene(), {}, 2);
  c.setCompareIntegrator(directByLight(LightMeasure::Area));
  c.setCompare(true);
  ASSERT_TRUE(waitUntil([&] { return c.progress().spp >= 3 && c.compareProgress().spp >= 3; }));

  // Left strategy: the left restarts, the right keeps accumulating.
  uint64_t left = c.restartCount(), right = c.compareRestartCount();
  uint32_t rightSpp = c.compareProgress().spp;
  RenderSettings s = c.settings();
  s.integrator = withCountsOf(directByHemisphere(HemisphereWarp::Uniform), s.integrator);
  c.setSettings(s);
  EXPECT_EQ(c.restartCount(), left + 1);
  EXPECT_EQ(c.compareRestartCount(), right);
  EXPECT_GE(c.compareProgress().spp, rightSpp);
  ASSERT_TRUE(waitUntil([&] { return c.compareProgress().spp >= rightSpp + 2; }));
  EXPECT_EQ(strategyLabel(c.engine().job()->settings.integrator),
            strategyLabel(directByHemisphere(HemisphereWarp::Uniform)));
  EXPECT_EQ(strategyLabel(c.compareEngine().job()->settings.integrator),
            strategyLabel(directByLight(LightMeasure::Area)));

  // Right strategy: only the right restarts.
  ASSERT_TRUE(waitUntil([&] { return c.progress().spp >= 3; }));
  uint32_t leftSpp = c.progress().spp;
  left = c.restartCount();
  c.setCompareIntegrator(directByLight(LightMeasure::SolidAngle));
  EXPECT_EQ(c.restartCount(), left);
  EXPECT_EQ(c.compareRestartCount(), right + 1);
  EXPECT_GE(c.progress().spp, leftSpp);
  EXPECT_EQ(strategyLabel(c.compareEngine().job()->settings.integrator),
            strategyLabel(directByLight(LightMeasure::SolidAngle)));

  // The camera is shared: moving it restarts both sides.
  right = c.compareRestartCount();
  c.setFov(c.settings().camera.fovDegrees + 5.f);
  EXPECT_EQ(c.restartCount(), left + 1);
  EXPECT_EQ(c.compareRestartCount(), right + 1);
  EXPECT_EQ(c.compareEngine().job()->settings.camera.fovDegrees, c.settings().camera.fovDegrees);
}

// The "MIS light share" view: offered only while a mis row renders and compare mode is off; a change
// that stops offering it turns it off; its snapshots are split films shown with the share map.
TEST(ViewerController, LightShareViewIsOfferedForMisStrategiesOnly) {
  ui::ViewerController c(smallDefaultScene(), {}, 2);
  c.start();
  EXPECT_FALSE(c.lightShareOffered());  // direct/solid-angle
  c.setLightShareView(true);
  EXPECT_FALSE(c.lightShareView());

  RenderSettings s = c.settings();
  s.integrator = directByMis(LightMeasure::ProjectedSolidAngle, MisHeuristic::Balance);
  c.setSettings(s);
  ASSERT_TRUE(c.lightShareOffered());
  const uint64_t restarts = c.restartCount();
  c.setLightShareView(true);
  EXPECT_TRUE(c.lightShareView());
  EXPECT_EQ(c.restartCount(), restarts + 1);  // the split output is another accumulation
  ASSERT_TRUE(waitUntil([&] {
    c.pollSnapshot(false);
    return c.snapshotIsLightShare() && c.snapshot().spp >= 2;
  }));
  EXPECT_EQ(c.shownDisplay().falseColour, ui::FalseColour::MisLightShare);
  EXPECT_EQ(c.display.falseColour, ui::FalseColour::None);  // the user's choice is kept for later
  // The split's channels are luminances >= 0; the built-in scene's floor gets a share.
  int withShare = 0;
  for (int y = 0; y < c.snapshot().mean.height; ++y)
    for (int x = 0; x < c.snapshot().mean.width; ++x) {
      const float share = lightShare(c.snapshot().mean.at(x, y));
      EXPECT_LE(share, 1.f);
      withShare += share >= 0.f;
    }
  EXPECT_GT(withShare, 100);

  // Another mis row keeps it; compare mode and a non-mis strategy turn it off.
  s.integrator = directByMis(LightMeasure::Area, MisHeuristic::Power);
  c.setSettings(s);
  EXPECT_TRUE(c.lightShareView());
  c.setCompare(true);
  EXPECT_FALSE(c.lightShareOffered());
  EXPECT_FALSE(c.lightShareView());
  c.setCompare(false);
  c.setLightShareView(true);
  EXPECT_TRUE(c.lightShareView());
  s.integrator = directByHemisphere(HemisphereWarp::Cosine);
  c.setSettings(s);
  EXPECT_FALSE(c.lightShareOffered());
  EXPECT_FALSE(c.lightShareView());
  ASSERT_TRUE(waitUntil([&] {
    c.pollSnapshot(false);
    return !c.snapshotIsLightShare() && c.snapshot().spp >= 1;
  }));
  EXPECT_EQ(c.shownDisplay().falseColour, ui::FalseColour::None);
}

// Saved in the light-share view: the PNG is the map, the EXR the split with its metadata.
TEST(ViewerController, LightShareViewSavesTheMapAndTheSplit) {
  ui::ViewerController c(smallDefaultScene(), {{"integrator.measure", "mis"}}, 2);
  RenderSettings s = c.settings();
  s.integrator = directByMis(LightMeasure::SolidAngle, MisHeuristic::Power);
  c.setSettings(s);
  c.setLightShareView(true);
  ASSERT_TRUE(waitUntil([&] {
    c.pollSnapshot(false);
    return c.snapshotIsLightShare() && c.snapshot().spp >= 2;
  }));
  c.setPaused(true);
  c.pollSnapshot(false);
  const fs::path dir = fs::temp_directory_path() / ("penumbra-share-" + std::to_string(getpid()));
  fs::create_directories(dir);
  c.saveImage((dir / "share.png").string());
  const Image png = readPng((dir / "share.png").string());
  const Image expected = ui::lightShareMapImage(c.snapshot().mean);
  ASSERT_EQ(png.width, expected.width);
  size_t differing = 0;
  for (size_t i = 0; i < png.rgb.size(); ++i) differing += toSrgb8(png.rgb[i]) != toSrgb8(expected.rgb[i]);
  EXPECT_EQ(differing, 0u);
  fs::remove_all(dir);
}
