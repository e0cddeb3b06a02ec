// End-to-end viewer tests: screenshots of the real UI rendered offscreen (penumbra-offscreen, OSMesa)
// and in a real GLFW window under Xvfb, compared with `penumbra render` of the same scene, spp and
// seed. The controller behind the UI is unit-tested in app/ui/viewer_controller_test.cpp.
#include <gtest/gtest.h>

#include "tests/run_command.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

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
  int sidebar = 0;            // the panel column's width
  float panelOverflow = 1e9;  // how far the panels' widest item passes the column's content region
  std::map<std::string, float> sections;  // each section header's top
};

Layout parseLayout(const std::string& out) {
  Layout l;
  size_t p = out.find("image-rect ");
  if (p != std::string::npos)
    std::sscanf(out.c_str() + p, "image-rect %f %f %d %d %f", &l.x, &l.y, &l.w, &l.h, &l.zoom);
  if ((p = out.find("sidebar ")) != std::string::npos) std::sscanf(out.c_str() + p, "sidebar %d", &l.sidebar);
  if ((p = out.find("panel-overflow ")) != std::string::npos)
    std::sscanf(out.c_str() + p, "panel-overflow %f", &l.panelOverflow);
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    char name[64];
    float y = 0;
    if (std::sscanf(line.c_str(), "section %63s %f", name, &y) == 2) l.sections[name] = y;
  }
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
  ASSERT_GT(l.sidebar, 0);
  ASSERT_GE(l.x, float(l.sidebar)) << "the image must be right of the panel column";

  // Panels: the sidebar is not the background, and has text (bright) pixels.
  const uint8_t bg[3] = {41, 41, 43};  // glClearColor 0.16, 0.16, 0.17
  int notBg = 0, bright = 0, total = 0;
  for (int y = 0; y < ui.height; y += 2)
    for (int x = 0; x < l.sidebar; x += 2) {
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
  RunResult r =
      test::runUnderXvfb(std::string(PENUMBRA_BINARY) + " view " + defaultSceneFile() + " " + kSets +
                             " --frames 30 --window 720x560 --print-layout --screenshot " + shot,
                         140);
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

// The MIS light share view: shaders/display.frag (uView 3) shows the same map as the CPU tone mapping
// (app/ui/light_share_map.h), pixel for pixel, and the map has colours (it is not the colour view).
TEST(ViewerOffscreen, LightShareViewIsTheSameMapOnTheShaderAndTheCpuPath) {
  Image shots[2];
  Layout layouts[2];
  const char* modes[] = {"cpu", "shader"};
  for (int i = 0; i < 2; ++i) {
    const std::string shot = tempDir() + "/share-" + modes[i] + ".png";
    RunResult r = run(std::string("PENUMBRA_TONEMAP=") + modes[i] + " " + PENUMBRA_OFFSCREEN_BINARY +
                      " view " + defaultSceneFile() + " " + kSets +
                      " --set integrator.measure=mis --view mis-light-share --frames 3 --window 720x560"
                      " --print-layout --screenshot " +
                      shot);
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find(std::string("tone mapping: ") + modes[i]), std::string::npos) << r.out;
    shots[i] = readPng(shot);
    layouts[i] = parseLayout(r.out);
  }
  const Layout& l = layouts[0];
  ASSERT_GT(l.w, 0);
  int worst = 0, red = 0;
  for (int y = 0; y < l.h; ++y)
    for (int x = 0; x < l.w; ++x) {
      const int sx = int(l.x + (x + 0.5f) * l.zoom), sy = int(l.y + (y + 0.5f) * l.zoom);
      for (int c = 0; c < 3; ++c)
        worst =
            std::max(worst, std::abs(int(byteAt(shots[0], sx, sy, c)) - int(byteAt(shots[1], sx, sy, c))));
      red += byteAt(shots[0], sx, sy, 0) > byteAt(shots[0], sx, sy, 2) + 60;  // mostly light sampling
    }
  EXPECT_LE(worst, 1);
  EXPECT_GT(red, l.w * l.h / 10);
}

TEST(ViewerOffscreen, LightShareViewWithoutAMisStrategyExitsWithCode2) {
  RunResult r = run(std::string(PENUMBRA_OFFSCREEN_BINARY) + " view " + defaultSceneFile() +
                    " --view mis-light-share --frames 1");
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("needs a mis strategy"), std::string::npos) << r.out;
}

// docs/viewer.md: nothing below the integrator section moves when the strategy changes. Every
// strategy of the list (and the rows a light selection, a fallback and no shading samples add or
// take away) puts the sections below at the same height.
TEST(ViewerOffscreen, SectionsBelowTheIntegratorStayPutWhateverTheStrategy) {
  const std::vector<std::string> strategies = {
      "--set integrator.measure=solid-angle",
      "--set integrator.measure=area --set integrator.lightSelection=power",
      "--set integrator.measure=hemisphere --set integrator.warp-type=uniform-hemisphere",
      "--set integrator.measure=mis",
      "--set integrator.type=ao",
      "--set integrator.type=simple",
      "--set integrator.type=normals"};
  std::map<std::string, float> first;
  for (const std::string& sets : strategies) {
    RunResult r = run(std::string(PENUMBRA_OFFSCREEN_BINARY) + " view " + defaultSceneFile() + " " + kSets +
                      " " + sets + " --frames 2 --no-wait --window 1280x800 --print-layout --screenshot " +
                      tempDir() + "/sections.png");
    ASSERT_EQ(r.exitCode, 0) << sets << "\n" << r.out;
    const Layout l = parseLayout(r.out);
    ASSERT_EQ(l.sections.size(), 7u) << r.out;
    if (first.empty()) {
      first = l.sections;
      continue;
    }
    // Measured from the integrator's header: a --set of another integrator type leaves unused
    // properties, whose warnings line in the Scene panel above moves everything alike.
    for (const char* below : {"Sampler", "Camera", "Display", "Stats", "Convergence"})
      EXPECT_EQ(l.sections.at(below) - l.sections.at("Integrator"), first.at(below) - first.at("Integrator"))
          << below << " moved with " << sets;
  }
}

// A small window keeps most of its width for the image, and no panel text is cut off at the
// column's edge (it wraps), at every size the docs show.
TEST(ViewerOffscreen, PanelsShrinkWithTheWindowAndNothingIsCutOff) {
  // The built-in scene (no reference); a scene with a closed-form reference (the convergence plot,
  // its legend and its buttons); an unreadable reference (a long error message).
  const std::string analytic = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/analytic/plane-sphere-light.xml";
  const std::string badReference = tempDir() + "/no-such-directory/a-reference-whose-name-is-long.exr";
  const std::vector<std::string> cases = {
      defaultSceneFile() + " " + kSets,
      analytic + " --set sampler.sampleCount=8",
      analytic + " --set sampler.sampleCount=8 --reference " + badReference,
  };
  for (const std::string& scene : cases)
    for (const char* window : {"640x480", "1280x800", "1920x1080"}) {
      RunResult r = run(std::string(PENUMBRA_OFFSCREEN_BINARY) + " view " + scene + " --frames 8 --window " +
                        window + " --print-layout --screenshot " + tempDir() + "/fit.png");
      ASSERT_EQ(r.exitCode, 0) << r.out;
      const Layout l = parseLayout(r.out);
      const int width = std::atoi(window);
      EXPECT_LE(l.sidebar, width * 2 / 5) << window << ": the panels take most of the window";
      EXPECT_GE(l.x, float(l.sidebar)) << window;
      EXPECT_LE(l.panelOverflow, 0.5f)
          << window << " " << scene << ": an item passes the column's edge (cut off)";
    }
}

// A reference given with --reference that cannot be read is shown in the Convergence panel; the
// viewer runs on.
TEST(ViewerOffscreen, AnUnreadableReferenceIsShownAndTheViewerRunsOn) {
  const std::string analytic = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/analytic/plane-sphere-light.xml";
  RunResult r = run(std::string(PENUMBRA_OFFSCREEN_BINARY) + " view " + analytic +
                    " --set sampler.sampleCount=4 --frames 4 --window 640x480 --print-layout --reference " +
                    tempDir() + "/missing.exr --screenshot " + tempDir() + "/missing-reference.png");
  EXPECT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.out.find("reference-error " + tempDir() + "/missing.exr: cannot open"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("wrote "), std::string::npos) << r.out;
}

// The compare divider is a light line between dark outlines: visible over a white floor.
TEST(ViewerOffscreen, CompareDividerHasAContrastingOutline) {
  const std::string shot = tempDir() + "/divider.png";
  RunResult r =
      run(std::string(PENUMBRA_OFFSCREEN_BINARY) + " view " + defaultSceneFile() + " " + kSets +
          " --compare area --frames 3 --no-wait --window 720x560 --print-layout --screenshot " + shot);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const Layout l = parseLayout(r.out);
  const Image ui = readPng(shot);
  // The divider sits at half the image (the default); find its light core on the middle row.
  const int y = int(l.y + l.h * l.zoom * 0.5f);
  const int mid = int(l.x + l.w * l.zoom * 0.5f);
  int core = -1;
  for (int x = mid - 3; x <= mid + 3 && core < 0; ++x)
    if (byteAt(ui, x, y, 0) >= 240 && byteAt(ui, x + 1, y, 0) >= 240 && byteAt(ui, x, y, 1) >= 240) core = x;
  ASSERT_GE(core, 0) << "no divider core near x = " << mid;
  // Below the labels above each side (they are drawn over the top of the image).
  for (int row = int(l.y) + 48; row < int(l.y + l.h * l.zoom) - 1; ++row) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_LE(byteAt(ui, core - 1, row, c), 20) << "left outline, row " << row;
      EXPECT_LE(byteAt(ui, core + 2, row, c), 20) << "right outline, row " << row;
      EXPECT_GE(byteAt(ui, core, row, c), 235) << "core, row " << row;
    }
    if (HasFailure()) break;
  }
}

// A --set value the scene builder refuses is blamed on the --set (exit code 2), not on a line of
// the file; malformed XML is described in words.
TEST(ViewerOffscreen, InvalidSetAndMalformedXmlAreReportedInWords) {
  RunResult r = run(std::string(PENUMBRA_OFFSCREEN_BINARY) + " view " + defaultSceneFile() +
                    " --set sampler.sampleCount=0 --frames 1");
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("--set sampler.sampleCount=0: sampleCount must be an integer in [1, 16777216], got 0"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find(".xml:"), std::string::npos) << "blamed on a line of the file: " << r.out;
  const std::string bad = tempDir() + "/malformed.xml";
  std::ofstream(bad) << "<scene>\n  <integrator type=\"direct\">\n</scene>\n";
  r = run(std::string(PENUMBRA_OFFSCREEN_BINARY) + " view " + bad + " --frames 1");
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("malformed.xml:2: malformed XML: <integrator> starting on this line is not closed"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("XML_ERROR"), std::string::npos) << r.out;
}
