// ViewerController as a first-time user meets it: a saved scene reopens from anywhere, compare mode
// offers and renders only strategies that apply, reload keeps live changes, restart resumes, the
// readouts say what they show, the title and target follow the scene, loading is visible, the orbit
// stays above the horizon, and compare mode is equal-time.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>

#include "app/ui/readouts.h"
#include "app/ui/viewer_controller.h"
#include "app/ui/wait_until_test_support.h"
#include "core/math/error.h"
#include "core/scene/scene_builder.h"

namespace fs = std::filesystem;
using namespace penumbra;

namespace {

// Loads and first passes of the assignment scenes on a loaded machine take longer.
bool waitUntil(const std::function<bool()>& done) {
  return test::waitUntil(done, std::chrono::seconds(60));
}

// A fresh directory under the system temp dir, removed when the test ends.
struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("penumbra-first-use-" + std::to_string(getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

void writeFile(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

// A small scene in `xml` form: `integrator` and `sampler` lines are substituted.
std::string sceneXml(const std::string& integrator,
                     const std::string& sampler = "<integer name=\"seed\" value=\"1\"/>") {
  return "<scene>\n"
         "  <sampler type=\"independent\"><integer name=\"sampleCount\" value=\"4\"/>" +
         sampler +
         "</sampler>\n"
         "  " +
         integrator +
         "\n"
         "  <shape type=\"sphere\"><point name=\"center\" value=\"0,0,0\"/><float name=\"radius\" "
         "value=\"0.3\"/>"
         "<bsdf type=\"diffuse\"/></shape>\n"
         "  <shape type=\"plane\"><bsdf type=\"diffuse\"/><transform name=\"toWorld\"><scale "
         "value=\"5,1,5\"/>"
         "<translate value=\"0,-0.3,0\"/></transform></shape>\n"
         "  <emitter type=\"point\"><point name=\"position\" value=\"1,2,1\"/><color name=\"radiance\" "
         "value=\"1,1,1\"/></emitter>\n"
         "  <camera type=\"perspective\">\n"
         "    <transform name=\"toWorld\"><lookat target=\"0,0,-0.4\" origin=\"0,1,2\" "
         "up=\"0,1,0\"/></transform>\n"
         "    <float name=\"fov\" value=\"40\"/><integer name=\"width\" value=\"24\"/><integer "
         "name=\"height\" value=\"16\"/>\n"
         "  </camera>\n"
         "</scene>\n";
}

const char* kDirect =
    "<integrator type=\"direct\"><string name=\"measure\" value=\"hemisphere\"/></integrator>";
const char* kAo = "<integrator type=\"ao\"><string name=\"sampler\" value=\"cosine\"/></integrator>";

// Renders to the controller's target spp and returns the finished image.
Image renderToEnd(ui::ViewerController& c) {
  c.start();
  EXPECT_TRUE(waitUntil([&] {
    c.pollSnapshot(false);
    return c.progress().finished && c.snapshot().spp == c.limits().targetSpp;
  }));
  return c.snapshot().mean;
}

}  // namespace

TEST(ViewerFirstUse, SavedSceneReopensFromAnotherDirectoryAndRendersTheSameImage) {
  TempDir tmp;
  const fs::path src = tmp.path / "src";
  fs::copy_file(PENUMBRA_SOURCE_DIR "/scenes/hw1/Tests/sphere-point.xml",
                (fs::create_directories(src), src / "s.xml"));
  fs::copy_file(PENUMBRA_SOURCE_DIR "/scenes/hw1/Tests/plane.obj", src / "plane.obj");
  const ui::ViewerController::Overrides small = {{"camera.width", "20"}, {"camera.height", "20"}};
  ui::ViewerController a(loadScene((src / "s.xml").string(), small), {}, 2);
  Image original = renderToEnd(a);

  // Written elsewhere (a sibling directory: a relative path exists) and to a second root-relative
  // place; both load and render the same pixels.
  for (const fs::path& out : {tmp.path / "out" / "deeper" / "saved.xml", tmp.path / "saved-here.xml"}) {
    fs::create_directories(out.parent_path());
    a.saveSceneAs(out.string());
    LoadedScene again;
    ASSERT_NO_THROW(again = loadScene(out.string())) << out;
    std::ifstream in(out);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text.find("\"plane.obj\""), std::string::npos) << text;  // rewritten, not copied
    EXPECT_NE(text.find("src/plane.obj"), std::string::npos) << text;
    ui::ViewerController b(std::move(again), {}, 2);
    Image reopened = renderToEnd(b);
    ASSERT_EQ(reopened.width, original.width);
    EXPECT_EQ(reopened.rgb, original.rgb) << out;
  }
}

TEST(ViewerFirstUse, CompareOffersOnlyApplicableStrategiesAndRendersWhatItShows) {
  // A direct-lighting scene without area lights (like the hw1 teapot).
  ui::ViewerController d(loadSceneFromString(sceneXml(kDirect), "d.xml", "."), {}, 2);
  ASSERT_FALSE(d.sceneHasAreaLights());
  EXPECT_TRUE(d.compareOffered());
  EXPECT_TRUE(d.comparableWithLeft(directByHemisphere(HemisphereWarp::Uniform)));
  EXPECT_FALSE(d.comparableWithLeft(directByLight(LightMeasure::Area)));  // needs area lights
  EXPECT_FALSE(d.comparableWithLeft(aoBy(HemisphereWarp::Uniform)));
  EXPECT_TRUE(strategyApplies(d.compareIntegrator(), false)) << strategyLabel(d.compareIntegrator());
  EXPECT_NE(strategyLabel(d.compareIntegrator()), strategyLabel(d.settings().integrator));
  EXPECT_EQ(d.renderedCompareIntegrator(), withCountsOf(d.compareIntegrator(), d.settings().integrator));
  d.setCompare(true);
  EXPECT_EQ(strategyLabel(d.compareEngine().job()->settings.integrator),
            strategyLabel(d.compareIntegrator()));

  // An AO scene: the right side is the other AO strategy, never a (black) direct one.
  ui::ViewerController ao(loadSceneFromString(sceneXml(kAo), "ao.xml", "."), {}, 2);
  EXPECT_TRUE(ao.compareOffered());
  EXPECT_EQ(strategyLabel(ao.compareIntegrator()), strategyLabel(aoBy(HemisphereWarp::Uniform)));
  EXPECT_EQ(strategyLabel(ao.renderedCompareIntegrator()), strategyLabel(aoBy(HemisphereWarp::Uniform)));

  // --compare: the message names exactly what is accepted; "all" is not claimed and not accepted.
  EXPECT_EQ(strategyLabel(ao.parseCompareStrategy("ao-cosine")), strategyLabel(aoBy(HemisphereWarp::Cosine)));
  EXPECT_EQ(strategyLabel(ao.parseCompareStrategy("cosine")), strategyLabel(aoBy(HemisphereWarp::Cosine)));
  try {
    ao.parseCompareStrategy("all");
    ADD_FAILURE() << "all accepted";
  } catch (const Error& e) {
    std::string msg = e.what();
    EXPECT_EQ(msg.find("expected all"), std::string::npos) << msg;
    EXPECT_NE(msg.find(": uniform-hemisphere, cosine-hemisphere"), std::string::npos) << msg;
  }
  EXPECT_THROW(ao.parseCompareStrategy("solid-angle"), Error);  // a direct strategy on an AO scene
}

TEST(ViewerFirstUse, ReloadKeepsLiveChangesUnlessTheFileChangedThem) {
  TempDir tmp;
  const fs::path file = tmp.path / "scene.xml";
  writeFile(file, sceneXml(kDirect));
  ui::ViewerController c(loadScene(file.string()), {}, 1);
  c.start();
  RenderSettings s = c.settings();
  s.integrator = withCountsOf(directByHemisphere(HemisphereWarp::Uniform),
                              s.integrator);  // chosen in the UI (the file: cosine)
  c.setSettings(s);
  c.orbit(30.f, 0.f);
  const glm::mat4 orbited = c.settings().camera.toWorld;

  // The file changes only the sampler's seed: the UI's integrator and camera survive.
  writeFile(file, sceneXml(kDirect, "<integer name=\"seed\" value=\"9\"/>"));
  ASSERT_TRUE(c.reloadScene());
  EXPECT_EQ(strategyLabel(c.settings().integrator),
            strategyLabel(directByHemisphere(HemisphereWarp::Uniform)));
  EXPECT_EQ(c.settings().camera.toWorld, orbited);
  EXPECT_EQ(c.settings().seed, 9u);
  EXPECT_NE(c.sceneStatus().find("reloaded scene.xml"), std::string::npos) << c.sceneStatus();
  EXPECT_NE(c.sceneStatus().find("integrator"), std::string::npos) << c.sceneStatus();
  EXPECT_NE(c.sceneStatus().find("camera"), std::string::npos) << c.sceneStatus();

  // The file changes the integrator itself (its shading samples): the file wins.
  writeFile(file, sceneXml("<integrator type=\"direct\"><string name=\"measure\" value=\"hemisphere\"/>"
                           "<integer name=\"nSamples\" value=\"3\"/></integrator>",
                           "<integer name=\"seed\" value=\"9\"/>"));
  ASSERT_TRUE(c.reloadScene());
  EXPECT_EQ(strategyLabel(c.settings().integrator),
            strategyLabel(directByHemisphere(HemisphereWarp::Cosine)));
  EXPECT_EQ(c.settings().integrator.samples, 3);
  EXPECT_EQ(c.settings().camera.toWorld, orbited);
}

TEST(ViewerFirstUse, RestartWhilePausedResumesAndOneSampleHasNoErrorEstimate) {
  ui::ViewerController c(
      loadSceneFromString(sceneXml(kDirect), "d.xml", ".", {{"sampler.sampleCount", "100000"}}), {}, 1);
  c.start();
  ASSERT_TRUE(waitUntil([&] { return c.progress().spp >= 1; }));
  c.setPaused(true);
  c.restart();
  EXPECT_FALSE(c.paused());
  ASSERT_TRUE(waitUntil([&] { return c.progress().spp >= 3; }));

  EXPECT_EQ(ui::probeErrorText(1, 0.f), "(no error estimate below 2 spp)");
  EXPECT_EQ(ui::probeErrorText(0, 0.f), "(no error estimate below 2 spp)");
  EXPECT_EQ(ui::probeErrorText(2, 0.25f), "± 0.25");
}

TEST(ViewerFirstUse, SampleCountAndTargetSppAreTiedWhileEqualAndTheUiSaysWhichStops) {
  ui::ViewerController c(loadSceneFromString(sceneXml(kDirect), "d.xml", "."), {}, 1);
  EXPECT_EQ(c.limits().targetSpp, 4u);
  EXPECT_EQ(c.stopText(), "stops at 4 spp (target spp)");
  RenderSettings s = c.settings();
  s.sampleCount = 64;
  c.setSettings(s);
  EXPECT_EQ(c.limits().targetSpp, 64u);  // raised with it
  RenderLimits l = c.limits();
  l.targetSpp = 10;  // the user's own target: no longer tied
  c.setLimits(l);
  s.sampleCount = 128;
  c.setSettings(s);
  EXPECT_EQ(c.limits().targetSpp, 10u);
  EXPECT_EQ(c.stopText(), "stops at 10 spp (target spp)");
}

TEST(ViewerFirstUse, TitleTargetAndZoomLabelFollowTheScene) {
  TempDir tmp;
  writeFile(tmp.path / "first.xml", sceneXml(kDirect));
  writeFile(tmp.path / "second.xml", sceneXml(kAo));
  ui::ViewerController c(loadScene((tmp.path / "first.xml").string()), {}, 1);
  EXPECT_NE(c.windowTitle().find("first.xml"), std::string::npos);
  ASSERT_TRUE(c.openScene((tmp.path / "second.xml").string()));
  EXPECT_NE(c.windowTitle().find("second.xml"), std::string::npos) << c.windowTitle();
  EXPECT_EQ(c.windowTitle().find("first.xml"), std::string::npos) << c.windowTitle();

  // The target shown is the scene's lookat target, exactly, and orbiting pivots about it.
  EXPECT_EQ(c.shownTarget(), Vec3(0.f, 0.f, -0.4f));
  EXPECT_FALSE(c.orbitCamera().moved);
  for (int i = 0; i < 20; ++i) c.orbit(13.f, -7.f);
  EXPECT_TRUE(c.orbitCamera().moved);
  EXPECT_EQ(c.shownTarget(), Vec3(0.f, 0.f, -0.4f));
  c.resetCamera();
  EXPECT_EQ(c.shownTarget(), Vec3(0.f, 0.f, -0.4f));
  EXPECT_FALSE(c.orbitCamera().moved);

  ui::DisplaySettings d;
  d.zoom = 3.f, d.fit = false;
  EXPECT_EQ(ui::zoomLabel(d, 0.5f), "3x");
  d.fit = true;  // Fit: the label shows the fitted zoom, not the last manual one
  EXPECT_EQ(ui::zoomLabel(d, 0.5f), "fit 0.5x");
}

TEST(ViewerFirstUse, LoadingIsVisibleUntilTheNewSceneIsAdopted) {
  TempDir tmp;
  writeFile(tmp.path / "next.xml", sceneXml(kAo));
  writeFile(tmp.path / "bad.xml", "<scene>\n<shape type=\"nope\"/>\n</scene>\n");
  ui::ViewerController c(loadSceneFromString(sceneXml(kDirect), "d.xml", "."), {}, 1);
  c.start();
  auto before = c.scene().scene;
  c.openSceneAsync((tmp.path / "next.xml").string());
  EXPECT_TRUE(c.loading());  // until pollSnapshot adopts the result, however fast the load was
  EXPECT_EQ(c.loadingPath(), (tmp.path / "next.xml").string());
  EXPECT_EQ(c.scene().scene, before);
  ASSERT_TRUE(waitUntil([&] {
    c.pollSnapshot(false);
    return !c.loading();
  }));
  EXPECT_NE(c.scene().path.find("next.xml"), std::string::npos);
  EXPECT_GT(c.loadSeconds(), 0.0);
  EXPECT_NE(c.sceneStatus().find("BVH build"), std::string::npos) << c.sceneStatus();

  // A failing load keeps the scene and reports the error.
  before = c.scene().scene;
  c.openSceneAsync((tmp.path / "bad.xml").string());
  ASSERT_TRUE(waitUntil([&] {
    c.pollSnapshot(false);
    return !c.loading();
  }));
  EXPECT_EQ(c.scene().scene, before);
  EXPECT_NE(c.sceneError().find("bad.xml:2"), std::string::npos) << c.sceneError();
}

TEST(ViewerFirstUse, OrbitStaysInTheScenesUpperHemisphere) {
  ui::ViewerController c(loadSceneFromString(sceneXml(kDirect), "d.xml", "."), {}, 1);
  auto elevation = [&] {
    Vec3 dir = glm::normalize(Vec3(c.settings().camera.toWorld[3]) - c.orbitCamera().target);
    return glm::dot(dir, c.orbitCamera().worldUp);
  };
  EXPECT_EQ(c.orbitCamera().worldUp, Vec3(0, 1, 0));  // the lookat's up, not the tilted camera's
  float lowest = 1.f;
  for (float dy : {10.f, -10.f})
    for (int i = 0; i < 400; ++i) {
      c.orbit(3.f, dy);
      lowest = std::min(lowest, elevation());
    }
  EXPECT_GE(lowest, -1e-4f);
  EXPECT_LT(lowest, 0.1f);  // it does go down to the horizon
}

TEST(ViewerFirstUse, CompareModeIsEqualTimeByDefault) {
  ui::ViewerController c(loadSceneFromString(sceneXml(kDirect), "d.xml", "."), {}, 2);
  EXPECT_EQ(c.effectiveLimits().targetSpp, 4u);
  c.setCompare(true);
  EXPECT_EQ(c.effectiveLimits().targetSpp, 0u);
  EXPECT_EQ(c.effectiveLimits().seconds, ui::ViewerController::kCompareSeconds);
  EXPECT_NE(c.stopText().find("equal time"), std::string::npos) << c.stopText();
  // A user's time budget is shared by both sides as it is.
  RenderLimits l;
  l.seconds = 3;
  c.setLimits(l);
  EXPECT_EQ(c.effectiveLimits().seconds, 3.0);
  EXPECT_EQ(c.compareEngine().job()->settings.camera.toWorld, c.settings().camera.toWorld);
  c.setCompare(false);
  EXPECT_EQ(c.effectiveLimits().seconds, 3.0);
}
