// Viewer tests: the controller's restart rules (driven through its API, no GL), and screenshots of the
// real UI rendered offscreen (penumbra-offscreen, OSMesa) and in a real GLFW window under Xvfb,
// compared with `penumbra render` of the same scene, spp and seed.
#include <gtest/gtest.h>

#include "tests/run_command.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "app/ui/viewer_controller.h"
#include "core/image/image_io.h"
#include "core/image/tonemap.h"
#include "core/scene/scene_builder.h"

namespace fs = std::filesystem;
using namespace penumbra;

namespace {

const char* kSets =
    "--set camera.width=96 --set camera.height=72 --set sampler.sampleCount=4 --set sampler.seed=3";

std::string tempDir() {
  // One directory per test process, removed when the process exits.
  static const struct Dir {
    fs::path path = fs::temp_directory_path() / ("penumbra-viewer-test-" + std::to_string(::getpid()));
    ~Dir() { fs::remove_all(path); }
  } dir;
  fs::create_directories(dir.path);
  return dir.path.string();
}

// The built-in scene as a file, so `penumbra render` (which needs a path) renders the same scene.
std::string defaultSceneFile() {
  std::string p = tempDir() + "/default.xml";
  if (!fs::exists(p)) std::ofstream(p) << defaultSceneXml();
  return p;
}

using RunResult = test::CommandResult;
RunResult run(const std::string& cmd) {
  return test::runCommand(cmd);
}

struct Layout {
  float x = -1, y = -1, zoom = 0;
  int w = 0, h = 0;
};

Layout parseLayout(const std::string& out) {
  Layout l;
  size_t p = out.find("image-rect ");
  if (p != std::string::npos)
    std::sscanf(out.c_str() + p, "image-rect %f %f %d %d %f", &l.x, &l.y, &l.w, &l.h, &l.zoom);
  return l;
}

uint8_t byteAt(const Image& img, int x, int y, int c) {
  return toSrgb8(img.rgb[img.index(x, y) + c]);
}

// Checks a UI screenshot: panels drawn in the sidebar, background around the image, and the image area
// equal to the headless render after the same tone mapping (within 1/255).
void checkScreenshot(const std::string& shot, const Layout& l, const std::string& reference) {
  Image ui = readPng(shot);
  Image ref = readPng(reference);
  ASSERT_EQ(l.w, ref.width);
  ASSERT_EQ(l.h, ref.height);
  ASSERT_GT(l.zoom, 0.f);
  ASSERT_GE(l.x, 400.f) << "the image must be right of the 400-pixel panel column";

  // Panels: the sidebar is not the background, and has text (bright) pixels.
  const uint8_t bg[3] = {41, 41, 43};  // glClearColor 0.16, 0.16, 0.17
  int notBg = 0, bright = 0, total = 0;
  for (int y = 0; y < ui.height; y += 2)
    for (int x = 0; x < 400; x += 2) {
      ++total;
      bool isBg = true;
      for (int c = 0; c < 3; ++c) isBg = isBg && std::abs(int(byteAt(ui, x, y, c)) - bg[c]) <= 1;
      notBg += !isBg;
      bright += byteAt(ui, x, y, 0) > 180 && byteAt(ui, x, y, 1) > 180;
    }
  EXPECT_GT(notBg, total * 9 / 10) << "the panel column looks empty";
  EXPECT_GT(bright, 200) << "no text in the panels";
  // Background just right of the panels, away from the image.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(byteAt(ui, ui.width - 3, 2, c), bg[c], 1);

  // The image area: every image pixel, sampled at the centre of its zoomed footprint.
  int worst = 0;
  for (int y = 0; y < ref.height; ++y)
    for (int x = 0; x < ref.width; ++x)
      for (int c = 0; c < 3; ++c) {
        int sx = int(l.x + (x + 0.5f) * l.zoom), sy = int(l.y + (y + 0.5f) * l.zoom);
        worst = std::max(worst, std::abs(int(byteAt(ui, sx, sy, c)) - int(byteAt(ref, x, y, c))));
      }
  EXPECT_LE(worst, 1) << "image area differs from `penumbra render` by " << worst << "/255";
}

std::string headlessReference() {
  static std::string path;
  if (!path.empty()) return path;
  std::string p = tempDir() + "/reference.png";
  RunResult r = run(std::string(PENUMBRA_BINARY) + " render " + defaultSceneFile() + " " + kSets +
                    " --spp 4 --seed 3 -o " + p);
  EXPECT_EQ(r.exitCode, 0) << r.out;
  path = p;
  return path;
}

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
  ASSERT_EQ(s.integrator.measure, DirectMeasure::SolidAngle);
  s.integrator.measure = DirectMeasure::Area;
  c.setSettings(s);
  EXPECT_EQ(c.restartCount(), restarts + 1);
  EXPECT_LT(c.progress().spp, running);
  EXPECT_EQ(c.settings().integrator.measure, DirectMeasure::Area);
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
  s.integrator.type = IntegratorType::Ao;
  s.integrator.warp = HemisphereWarp::Uniform;
  s.integrator.samples = 3;
  c.setSettings(s);
  EXPECT_EQ(c.restartCount(), r0 + 4);

  // The live settings as scene XML parse back to the same settings.
  LoadedScene again = loadSceneFromString(c.liveSceneXml(), "live.xml", ".");
  const RenderSettings& t = again.settings;
  EXPECT_EQ(t.seed, 17u);
  EXPECT_EQ(t.samplerKind, SamplerKind::Stratified);
  EXPECT_EQ(t.integrator.type, IntegratorType::Ao);
  EXPECT_EQ(t.integrator.warp, HemisphereWarp::Uniform);
  EXPECT_EQ(t.integrator.samples, 3);
  EXPECT_EQ(t.camera.width, 48);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(t.camera.toWorld[i][j], c.settings().camera.toWorld[i][j], 1e-5f);

  c.resetCamera();
  EXPECT_EQ(c.settings().camera.toWorld, before);
}

TEST(ViewerController, InvalidSceneKeepsTheLastGoodOneAndShowsFileAndLine) {
  std::string bad = tempDir() + "/bad.xml";
  std::ofstream(bad)
      << "<scene>\n  <integrator type=\"direct\">\n    <integer name=\"nSamples\" value=\"x\"/>\n"
         "  </integrator>\n</scene>\n";
  ui::ViewerController c(smallDefaultScene(), {}, 1);
  c.start();
  auto scene = c.scene().scene;
  EXPECT_FALSE(c.openScene(bad));
  EXPECT_NE(c.sceneError().find("bad.xml:3"), std::string::npos) << c.sceneError();
  EXPECT_EQ(c.scene().scene, scene);
}

TEST(ViewerOffscreen, PanelsDrawAndImageAreaEqualsHeadlessRender) {
  std::string shot = tempDir() + "/offscreen.png";
  RunResult r = run(std::string(PENUMBRA_OFFSCREEN_BINARY) + " view " + defaultSceneFile() + " " + kSets +
                    " --frames 3 --window 720x560 --print-layout --screenshot " + shot);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.out.find("spp 4"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("tone mapping: cpu"), std::string::npos) << r.out;  // llvmpipe: software GL
  checkScreenshot(shot, parseLayout(r.out), headlessReference());
}

// On llvmpipe the viewer tone maps on the CPU (display_tonemap.cpp); hardware GL uses
// shaders/display.frag. Both must show exactly the headless render.
TEST(ViewerOffscreen, ShaderToneMappingAlsoEqualsHeadlessRender) {
  std::string shot = tempDir() + "/offscreen-shader.png";
  RunResult r = run(std::string("PENUMBRA_TONEMAP=shader ") + PENUMBRA_OFFSCREEN_BINARY + " view " +
                    defaultSceneFile() + " " + kSets +
                    " --frames 3 --window 720x560 --print-layout --screenshot " + shot);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.out.find("spp 4"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("tone mapping: shader"), std::string::npos) << r.out;
  checkScreenshot(shot, parseLayout(r.out), headlessReference());
}

TEST(ViewerOffscreen, ViewOffscreenFlagRunsTheOffscreenBinary) {
  std::string shot = tempDir() + "/flag.png";
  RunResult r = run(std::string(PENUMBRA_BINARY) + " view --offscreen " + defaultSceneFile() + " " + kSets +
                    " --frames 2 --window 720x560 --print-layout --screenshot " + shot);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.out.find("OSMesa"), std::string::npos) << r.out;
  checkScreenshot(shot, parseLayout(r.out), headlessReference());
}

TEST(ViewerOffscreen, NoDisplayFallsBackToOffscreenScreenshot) {
  std::string dir = tempDir() + "/nodisplay";
  fs::create_directories(dir);
  RunResult r = run("cd " + dir + " && env -u DISPLAY -u WAYLAND_DISPLAY " + PENUMBRA_BINARY + " view " +
                    defaultSceneFile() + " " + kSets);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.out.find("no display"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir + "/penumbra-view.png")) << r.out;
}

TEST(ViewerOffscreen, SceneErrorsExitWithCode2) {
  RunResult r = run(std::string(PENUMBRA_OFFSCREEN_BINARY) + " view /nonexistent/scene.xml --frames 1");
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("scene.xml"), std::string::npos) << r.out;
}

TEST(ViewerWindow, RealWindowUnderXvfb) {
  if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "xvfb-run is not installed (apt-get install xvfb xauth): skipping the real-window test";
  std::string shot = tempDir() + "/window.png";
  // xvfb-run -a can race another X server starting at the same moment; the viewer then falls back to
  // offscreen. Retry a couple of times before judging.
  RunResult r;
  for (int attempt = 0; attempt < 3; ++attempt) {
    r = run("xvfb-run -a -n " + std::to_string(140 + 7 * attempt) + " -s '-screen 0 1024x768x24' " +
            std::string(PENUMBRA_BINARY) + " view " + defaultSceneFile() + " " + kSets +
            " --frames 30 --window 720x560 --print-layout --screenshot " + shot);
    if (r.exitCode == 0 && r.out.find("GLFW") != std::string::npos) break;
  }
  ASSERT_EQ(r.exitCode, 0) << r.out;
  ASSERT_NE(r.out.find("GLFW"), std::string::npos) << r.out;
  Layout l = parseLayout(r.out);
  // The window shows whatever spp it reached in 30 frames; the panels must be there, and the image
  // equals the headless render once the (tiny) accumulation finished.
  if (r.out.find("spp 4") != std::string::npos)
    checkScreenshot(shot, l, headlessReference());
  else {
    Image ui = readPng(shot);
    EXPECT_EQ(ui.width, 720);
  }
}

namespace {

template <class F>
bool waitUntil(F done) {
  auto t0 = std::chrono::steady_clock::now();
  while (!done()) {
    if (std::chrono::steady_clock::now() - t0 > std::chrono::seconds(30)) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

IntegratorDesc directWith(DirectMeasure m) {
  IntegratorDesc d;
  d.type = IntegratorType::Direct;
  d.measure = m;
  return d;
}

}  // namespace

TEST(ViewerCompare, EnablingStartsASecondAccumulationDisablingStopsIt) {
  ui::ViewerController c(smallDefaultScene(), {}, 2);
  c.start();
  EXPECT_FALSE(c.compareEnabled());
  c.setCompareIntegrator(directWith(DirectMeasure::Area));  // compare off: nothing starts
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
  EXPECT_EQ(c.compareEngine().job()->settings.integrator.measure, DirectMeasure::Area);
  EXPECT_EQ(c.engine().job()->settings.integrator.measure, DirectMeasure::SolidAngle);
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
  c.setCompareIntegrator(directWith(DirectMeasure::Area));
  c.setCompare(true);
  ASSERT_TRUE(waitUntil([&] { return c.progress().spp >= 3 && c.compareProgress().spp >= 3; }));

  // Left strategy: the left restarts, the right keeps accumulating.
  uint64_t left = c.restartCount(), right = c.compareRestartCount();
  uint32_t rightSpp = c.compareProgress().spp;
  RenderSettings s = c.settings();
  s.integrator.measure = DirectMeasure::Hemisphere;
  s.integrator.warp = HemisphereWarp::Uniform;
  c.setSettings(s);
  EXPECT_EQ(c.restartCount(), left + 1);
  EXPECT_EQ(c.compareRestartCount(), right);
  EXPECT_GE(c.compareProgress().spp, rightSpp);
  ASSERT_TRUE(waitUntil([&] { return c.compareProgress().spp >= rightSpp + 2; }));
  EXPECT_EQ(c.engine().job()->settings.integrator.measure, DirectMeasure::Hemisphere);
  EXPECT_EQ(c.compareEngine().job()->settings.integrator.measure, DirectMeasure::Area);

  // Right strategy: only the right restarts.
  ASSERT_TRUE(waitUntil([&] { return c.progress().spp >= 3; }));
  uint32_t leftSpp = c.progress().spp;
  left = c.restartCount();
  c.setCompareIntegrator(directWith(DirectMeasure::SolidAngle));
  EXPECT_EQ(c.restartCount(), left);
  EXPECT_EQ(c.compareRestartCount(), right + 1);
  EXPECT_GE(c.progress().spp, leftSpp);
  EXPECT_EQ(c.compareEngine().job()->settings.integrator.measure, DirectMeasure::SolidAngle);

  // The camera is shared: moving it restarts both sides.
  right = c.compareRestartCount();
  c.setFov(c.settings().camera.fovDegrees + 5.f);
  EXPECT_EQ(c.restartCount(), left + 1);
  EXPECT_EQ(c.compareRestartCount(), right + 1);
  EXPECT_EQ(c.compareEngine().job()->settings.camera.fovDegrees, c.settings().camera.fovDegrees);
}
