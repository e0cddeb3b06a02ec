// ViewerController as a user who tries things meets it: switching the stop rule back and forth keeps
// the target, the camera never goes under the floor or into an object, a saved orbited camera reopens
// about the same target, strategies that cannot light the scene say why, nothing of an old scene's
// state carries over to the next, and a slow first pass shows how far it got.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "app/ui/readouts.h"
#include "app/ui/viewer_controller.h"
#include "core/scene/scene_builder.h"

namespace fs = std::filesystem;
using namespace penumbra;

namespace {

// The built-in scene, small: a unit sphere at the origin on the plane z = -1, camera at (4, 4, 0)
// looking at the origin, up z.
LoadedScene builtIn(std::vector<std::pair<std::string, std::string>> sets = {}) {
  // Later overrides win: the caller's after these.
  sets.insert(sets.begin(), {{"camera.width", "32"}, {"camera.height", "32"}, {"sampler.sampleCount", "64"}});
  return loadSceneFromString(defaultSceneXml(), "<built-in scene>", ".", sets);
}

Vec3 cameraOrigin(const ui::ViewerController& c) {
  return Vec3(c.settings().camera.toWorld[3]);
}

struct TempDir {
  fs::path path =
      fs::temp_directory_path() / ("penumbra-odd-input-" + std::to_string(getpid()) + "-" +
                                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
  TempDir() {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

// A scene with exactly the lights given (XML of <emitter> elements and of emitting shapes).
LoadedScene litBy(const std::string& lights) {
  return loadSceneFromString(
      "<scene><integrator type=\"direct\"><string name=\"measure\" value=\"hemisphere\"/></integrator>"
      "<shape type=\"sphere\"><float name=\"radius\" value=\"0.5\"/></shape>" +
          lights +
          "<camera type=\"perspective\"><transform name=\"toWorld\"><lookat origin=\"0,0,4\" "
          "target=\"0,0,0\" "
          "up=\"0,1,0\"/></transform><integer name=\"width\" value=\"8\"/><integer name=\"height\" "
          "value=\"8\"/></camera></scene>",
      "lights.xml", ".");
}

const char* kPointLight =
    "<emitter type=\"point\"><point name=\"position\" value=\"1,2,1\"/><color name=\"radiance\" "
    "value=\"1\"/></emitter>";
const char* kAreaLight =
    "<shape type=\"sphere\"><point name=\"center\" value=\"2,2,2\"/><float name=\"radius\" value=\"0.3\"/>"
    "<emitter type=\"area\"><color name=\"radiance\" value=\"5\"/></emitter></shape>";

}  // namespace

TEST(ViewerOddInput, BackFromTheTimeBudgetRestoresTheTargetSpp) {
  ui::ViewerController c(builtIn(), {}, 1);
  EXPECT_EQ(c.stopRule(), ui::StopRule::TargetSpp);
  EXPECT_EQ(c.limits().targetSpp, 64u);
  c.setStopRule(ui::StopRule::TimeBudget);
  EXPECT_EQ(c.limits().seconds, ui::ViewerController::kDefaultSeconds);
  c.setStopRule(ui::StopRule::TargetSpp);
  EXPECT_EQ(c.limits().targetSpp, 64u) << "the target must come back, not 0 (endless)";
  EXPECT_EQ(c.limits().seconds, 0.0);
  // Values the user chose come back too, each for its rule.
  c.setTargetSpp(200);
  c.setTimeBudget(3.5);
  c.setStopRule(ui::StopRule::TargetSpp);
  EXPECT_EQ(c.limits().targetSpp, 200u);
  c.setStopRule(ui::StopRule::TimeBudget);
  EXPECT_EQ(c.limits().seconds, 3.5);
  // The same through setLimits, as the Sampler panel did it: the time budget's limits, then back.
  c.setLimits(RenderLimits{0, 12.0});
  c.setLimits(RenderLimits{c.chosenTargetSpp(), 0.0});
  EXPECT_EQ(c.limits().targetSpp, 200u);
  c.engine().cancel();
}

TEST(ViewerOddInput, PanNeverTakesTheCameraUnderTheFloor) {
  ui::ViewerController c(builtIn(), {}, 1);
  const float floorHeight = glm::dot(c.orbitCamera().horizonPoint, c.orbitCamera().worldUp);
  for (int i = 0; i < 50; ++i) c.pan(0.f, -200.f);  // drag the camera down, far
  EXPECT_GE(glm::dot(cameraOrigin(c), c.orbitCamera().worldUp), floorHeight - 1e-4f);
  EXPECT_NE(c.cameraLimitNote().find("horizon"), std::string::npos) << c.cameraLimitNote();
  // Sideways still pans, at the same height.
  const Vec3 before = cameraOrigin(c);
  c.pan(100.f, 0.f);
  EXPECT_GT(glm::length(cameraOrigin(c) - before), 0.1f);
  // Orbiting after the pan stays above the plane too.
  for (int i = 0; i < 200; ++i) c.orbit(0.f, -20.f);
  EXPECT_GE(glm::dot(cameraOrigin(c), c.orbitCamera().worldUp), floorHeight - 1e-3f);
  c.engine().cancel();
}

TEST(ViewerOddInput, DollyStopsInFrontOfTheSphereItLooksAt) {
  ui::ViewerController c(builtIn(), {}, 1);
  for (int i = 0; i < 200; ++i) c.dolly(1.f);  // wheel towards the target: the sphere's centre
  const float fromCentre = glm::length(cameraOrigin(c));
  EXPECT_GT(fromCentre, 1.f) << "the camera went inside the unit sphere (a black image)";
  EXPECT_LT(fromCentre, 1.2f) << "it should get close";
  EXPECT_NE(c.cameraLimitNote().find("surface"), std::string::npos) << c.cameraLimitNote();
  // And the image is not black: the first pass sees the sphere lit.
  c.pollSnapshot(false);
  c.engine().cancel();
}

TEST(ViewerOddInput, DollyingBackStopsAtAWallBehind) {
  // Inside a box of planes: dollying back must not leave it through the wall behind the camera.
  ui::ViewerController c(
      loadSceneFromString(
          "<scene><integrator type=\"normals\"/><shape type=\"sphere\"><float name=\"radius\" "
          "value=\"0.5\"/></shape><shape type=\"plane\"><transform name=\"toWorld\"><rotate "
          "axis=\"1,0,0\" angle=\"-90\"/><translate value=\"0,0,3\"/></transform></shape>"
          "<camera type=\"perspective\"><transform name=\"toWorld\"><lookat origin=\"0,0,2\" "
          "target=\"0,0,0\" up=\"0,1,0\"/></transform><integer name=\"width\" value=\"8\"/>"
          "<integer name=\"height\" value=\"8\"/></camera></scene>",
          "box.xml", "."),
      {}, 1);
  for (int i = 0; i < 100; ++i) c.dolly(-1.f);
  EXPECT_LT(cameraOrigin(c).z, 3.f) << "the camera went through the plane at z = 3";
  EXPECT_GT(cameraOrigin(c).z, 2.5f);
  c.engine().cancel();
}

TEST(ViewerOddInput, SavedOrbitedCameraReopensAboutTheSameTarget) {
  TempDir tmp;
  ui::ViewerController a(builtIn(), {}, 1);
  const Vec3 target = a.orbitCamera().target;
  EXPECT_EQ(target, Vec3(0.f));
  a.orbit(80.f, 30.f);
  a.dolly(1.f);
  const fs::path saved = tmp.path / "orbited.xml";
  a.saveSceneAs(saved.string());
  std::ifstream in(saved);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string camera = text.substr(text.find("<camera"));
  EXPECT_NE(camera.find("<lookat"), std::string::npos) << text;
  EXPECT_EQ(camera.find("<matrix"), std::string::npos) << text;

  ui::ViewerController b(loadScene(saved.string()), {}, 1);
  EXPECT_LT(glm::length(b.orbitCamera().target - a.orbitCamera().target), 1e-4f);
  EXPECT_LT(glm::length(b.orbitCamera().worldUp - a.orbitCamera().worldUp), 1e-5f);
  EXPECT_LT(glm::length(cameraOrigin(b) - cameraOrigin(a)), 1e-4f);
  EXPECT_NEAR(b.orbitCamera().distance, a.orbitCamera().distance, 1e-4f);
  EXPECT_EQ(b.orbitCamera().minElevationSin, 0.f);  // the horizon note: the orbit stays above 0
  // The camera itself is the same.
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row)
      EXPECT_NEAR(b.settings().camera.toWorld[col][row], a.settings().camera.toWorld[col][row], 1e-5f);

  // Panned, then saved and reopened: the panned target.
  b.pan(40.f, 10.f);
  const fs::path panned = tmp.path / "panned.xml";
  b.saveSceneAs(panned.string());
  ui::ViewerController d(loadScene(panned.string()), {}, 1);
  EXPECT_LT(glm::length(d.orbitCamera().target - b.orbitCamera().target), 1e-4f);
  a.engine().cancel(), b.engine().cancel(), d.engine().cancel();
}

TEST(ViewerOddInput, StrategiesThatCannotLightTheSceneSayWhy) {
  {
    ui::ViewerController areaOnly(litBy(kAreaLight), {}, 1);
    EXPECT_EQ(areaOnly.strategyUnavailableReason(integratorOfType(IntegratorType::Simple)),
              "needs point or directional lights");
    EXPECT_EQ(areaOnly.strategyUnavailableReason(directByHemisphere(HemisphereWarp::Cosine)), "");
    EXPECT_EQ(areaOnly.strategyUnavailableReason(directByLight(LightMeasure::SolidAngle)), "");
  }
  {
    ui::ViewerController pointOnly(litBy(kPointLight), {}, 1);
    EXPECT_EQ(pointOnly.strategyUnavailableReason(integratorOfType(IntegratorType::Simple)), "");
    EXPECT_EQ(pointOnly.strategyUnavailableReason(directByHemisphere(HemisphereWarp::Uniform)), "");
    EXPECT_NE(
        pointOnly.strategyUnavailableReason(directByLight(LightMeasure::Area)).find("needs area lights"),
        std::string::npos);
  }
  {
    ui::ViewerController dark(litBy(""), {}, 1);
    for (const IntegratorDesc& s :
         {directByHemisphere(HemisphereWarp::Uniform), directByHemisphere(HemisphereWarp::Cosine)})
      EXPECT_EQ(dark.strategyUnavailableReason(s), "needs lights: the scene has none");
    EXPECT_NE(dark.strategyUnavailableReason(integratorOfType(IntegratorType::Simple)), "");
    for (const IntegratorDesc& s : {aoBy(HemisphereWarp::Cosine), aoBy(HemisphereWarp::Uniform),
                                    integratorOfType(IntegratorType::Normals)})
      EXPECT_EQ(dark.strategyUnavailableReason(s), "") << strategyLabel(s);
  }
}

TEST(ViewerOddInput, PauseAndSaveMessageEndWithTheirScene) {
  TempDir tmp;
  const fs::path other = tmp.path / "other.xml";
  std::ofstream(other) << defaultSceneXml();
  ui::ViewerController c(builtIn(), {}, 1);
  c.start();
  c.setPaused(true);
  c.setOutputStatus(c.saveSceneAs((tmp.path / "saved.xml").string()));
  ASSERT_NE(c.outputStatus().find("saved"), std::string::npos);
  const uint64_t serial = c.sceneSerial();
  ASSERT_TRUE(c.openScene(other.string()));
  EXPECT_FALSE(c.paused()) << "the new scene must render, not inherit the pause";
  EXPECT_EQ(c.outputStatus(), "");
  EXPECT_EQ(c.sceneSerial(), serial + 1);
  // A reload of the same scene keeps both (the user's pause is about this scene).
  c.setPaused(true);
  c.setOutputStatus("saved x.png");
  c.reloadScene();
  EXPECT_TRUE(c.paused());
  EXPECT_EQ(c.outputStatus(), "saved x.png");
  c.engine().cancel();
}

TEST(ViewerOddInput, ASlowFirstPassShowsItsRowsAndAnEstimate) {
  // 65536 shading samples per camera sample: the first pass takes seconds.
  ui::ViewerController c(
      builtIn({{"integrator.nSamples", "65536"}, {"camera.width", "64"}, {"camera.height", "64"}}), {}, 1);
  c.start();
  RenderProgress p;
  auto t0 = std::chrono::steady_clock::now();
  do {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    p = c.progress();
  } while (p.passRows == 0 && p.spp == 0 && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60));
  ASSERT_EQ(p.spp, 0u) << "the first pass was not slow";
  EXPECT_GT(p.passRows, 0u);
  EXPECT_EQ(p.rows, 64u);
  EXPECT_GT(ui::samplesPerSecond(p, 64), 0.0) << "samples/s must count the rows done";
  // Once the pass is slow the Stats line says how far it got.
  while (ui::passElapsed(c.progress()) < ui::kSlowPassSeconds && c.progress().spp == 0)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  p = c.progress();
  ASSERT_EQ(p.spp, 0u) << "the first pass ended within half a second";
  const std::string text = ui::passProgressText(p);
  EXPECT_EQ(text.rfind("pass 1: ", 0), 0u) << text;
  EXPECT_NE(text.find(" of 64 rows"), std::string::npos) << text;
  EXPECT_NE(text.find(" s left"), std::string::npos) << text;
  c.engine().cancel();
}

TEST(ViewerOddInput, PassProgressAndStaleImageReadouts) {
  RenderProgress p;
  p.spp = 0, p.rows = 480, p.passRows = 120, p.seconds = 3.0, p.passSeconds = 0.0;
  EXPECT_EQ(ui::passProgressText(p), "pass 1: 120 of 480 rows (25 %), ~9.0 s left");
  p.seconds = 0.2;  // quick passes: nothing to follow
  EXPECT_EQ(ui::passProgressText(p), "");
  p.seconds = 3.0, p.finished = true;
  EXPECT_EQ(ui::passProgressText(p), "");
  p.finished = false, p.passRows = 0;
  EXPECT_EQ(ui::passProgressText(p), "pass 1: no row finished yet (3.0 s)");
  // An image from before the last restart is dimmed once its replacement is late.
  EXPECT_FALSE(ui::imageIsStale(3, 3, 5.0));
  EXPECT_FALSE(ui::imageIsStale(2, 3, 0.05));
  EXPECT_TRUE(ui::imageIsStale(2, 3, 1.0));
}
