// End-to-end viewer tests: screenshots of the real UI rendered offscreen (penumbra-offscreen, OSMesa)
// and in a real GLFW window under Xvfb, compared with `penumbra render` of the same scene, spp and
// seed. The controller behind the UI is unit-tested in app/ui/viewer_controller_test.cpp.
#include <gtest/gtest.h>

#include "tests/run_command.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/image/image_io.h"
#include "core/image/tonemap.h"
#include "core/scene/scene_builder.h"

namespace fs = std::filesystem;
using namespace penumbra;

namespace {

const char* kSets =
    "--set camera.width=96 --set camera.height=72 --set sampler.sampleCount=4 --set sampler.seed=3";

std::string tempDir() {
  fs::path d = fs::temp_directory_path() / ("penumbra-viewer-test-" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d.string();
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

}  // namespace

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
