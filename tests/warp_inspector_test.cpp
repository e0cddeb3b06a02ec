// End-to-end warp inspector tests: the real UI rendered offscreen by `penumbra-offscreen warp --gui`
// (and in a window under Xvfb), read back from the screenshot. The model behind it is unit-tested in
// app/ui/warp_inspector_model_test.cpp.
#include <gtest/gtest.h>

#include "tests/run_command.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/image/image_io.h"
#include "core/image/tonemap.h"

namespace fs = std::filesystem;
using namespace penumbra;

namespace {

std::string tempDir() {
  // One directory per test process, removed when the process exits.
  static const struct Dir {
    fs::path path =
        fs::temp_directory_path() / ("penumbra-warp-inspector-test-" + std::to_string(::getpid()));
    ~Dir() { fs::remove_all(path); }
  } dir;
  fs::create_directories(dir.path);
  return dir.path.string();
}

using RunResult = test::CommandResult;
RunResult run(const std::string& cmd) {
  return test::runCommand(cmd);
}

struct Rect {
  int x = 0, y = 0, w = 0, h = 0;
};

Rect panelRect(const std::string& out, const std::string& name) {
  Rect r;
  size_t p = out.find("panel " + name + " ");
  if (p != std::string::npos)
    std::sscanf(out.c_str() + p + 7 + name.size(), "%d %d %d %d", &r.x, &r.y, &r.w, &r.h);
  return r;
}

// Mean absolute difference (0 ... 255) of two equally sized screen regions, from the inner 80 % of
// each (away from the frames).
double regionDifference(const Image& img, const Rect& a, const Rect& b) {
  double sum = 0;
  int n = 0;
  for (int j = a.h / 10; j < a.h - a.h / 10; ++j)
    for (int i = a.w / 10; i < a.w - a.w / 10; ++i)
      for (int c = 0; c < 3; ++c) {
        int va = toSrgb8(img.rgb[img.index(a.x + i, a.y + j) + c]);
        int vb = toSrgb8(img.rgb[img.index(b.x + i, b.y + j) + c]);
        sum += std::abs(va - vb);
        ++n;
      }
  return n ? sum / n : 255.0;
}

}  // namespace

TEST(WarpInspectorOffscreen, CosineHemisphereRendersAcceptsAndPanelsAgree) {
  std::string shot = tempDir() + "/inspector.png";
  RunResult r =
      run(std::string(PENUMBRA_OFFSCREEN_BINARY) +
          " warp cosine-hemisphere --gui --points 14 --window 1280x800 --print-layout --screenshot " + shot);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.out.find("verdict accepted"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("(stale)"), std::string::npos) << r.out;
  Image img = readPng(shot);
  ASSERT_EQ(img.width, 1280);
  Rect hist = panelRect(r.out, "histogram"), dens = panelRect(r.out, "density"),
       diff = panelRect(r.out, "difference");
  ASSERT_GT(hist.w, 50) << r.out;
  ASSERT_EQ(hist.w, dens.w);
  ASSERT_EQ(hist.h, dens.h);
  ASSERT_LE(dens.x + dens.w, img.width);
  ASSERT_LE(hist.y + hist.h, img.height);
  double close = regionDifference(img, hist, dens);
  std::printf("histogram vs density panels on screen: mean |difference| %.2f / 255\n", close);
  EXPECT_LT(close, 15.0) << "histogram and density panels differ on screen";
  // The density panel is not blank: bright (yellow) near the pole, dark near the horizon.
  int top = toSrgb8(img.rgb[img.index(dens.x + dens.w / 2, dens.y + 2) + 1]);
  int bottom = toSrgb8(img.rgb[img.index(dens.x + dens.w / 2, dens.y + dens.h - 3) + 1]);
  EXPECT_GT(top, bottom + 80);
  // The 3-D view above the panels shows coloured points (not only the background).
  int coloured = 0;
  for (int y = 40; y < hist.y - 60; y += 3)
    for (int x = 320; x < img.width; x += 3) {
      int rr = toSrgb8(img.rgb[img.index(x, y)]), gg = toSrgb8(img.rgb[img.index(x, y) + 1]),
          bb = toSrgb8(img.rgb[img.index(x, y) + 2]);
      coloured += std::max({rr, gg, bb}) - std::min({rr, gg, bb}) > 100;
    }
  EXPECT_GT(coloured, 2000) << "no warped points in the 3-D view";
  (void)diff;
}

TEST(WarpInspectorOffscreen, MismatchedPdfIsRejectedThroughPenumbraGuiOffscreen) {
  std::string shot = tempDir() + "/mismatch.png";
  RunResult r = run(std::string(PENUMBRA_BINARY) +
                    " warp cosine-hemisphere --gui --offscreen --mismatch --points 14"
                    " --window 1280x800 --print-layout --screenshot " +
                    shot);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.out.find("verdict rejected"), std::string::npos) << r.out;
  Image img = readPng(shot);
  Rect hist = panelRect(r.out, "histogram"), dens = panelRect(r.out, "density");
  ASSERT_GT(hist.w, 50) << r.out;
  double apart = regionDifference(img, hist, dens);
  std::printf("mismatched: histogram vs density panels on screen: mean |difference| %.2f / 255\n", apart);
  EXPECT_GT(apart, 16.0) << "a rejected pair should look different";
}

TEST(WarpInspectorCli, GuiOptionsNeedGui) {
  RunResult r = run(std::string(PENUMBRA_BINARY) + " warp cosine-hemisphere --points 10");
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("--gui"), std::string::npos) << r.out;
  r = run(std::string(PENUMBRA_BINARY) + " warp cosine-hemisphere --gui --offscreen --point-set sobol");
  EXPECT_EQ(r.exitCode, 2) << r.out;
}

// The inspector's inputs are checked as the CLI's (core/sampling/warp_params.h): the same messages
// from `penumbra warp --gui` as from the window's controls (app/ui/warp_inspector_model_test.cpp).
TEST(WarpInspectorCli, InvalidInspectorValuesAreRefusedWithTheSharedMessages) {
  RunResult r = run(std::string(PENUMBRA_BINARY) +
                    " warp cosine-hemisphere --gui --offscreen --point-set sampler --pixel=-5,0");
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("--pixel -5,0: expected a pixel X,Y with each coordinate 0 to 16383"),
            std::string::npos)
      << r.out;
  r = run(std::string(PENUMBRA_BINARY) + " warp cosine-hemisphere --gui --offscreen --points 25");
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("--points 25: expected the number of points as a power of two, 5 to 20"),
            std::string::npos)
      << r.out;
  r = run(std::string(PENUMBRA_BINARY) + " warp beckmann --gui --offscreen --param 0");
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("beckmann: --param is the roughness alpha and must be in [1e-06, 1000], got 0"),
            std::string::npos)
      << r.out;
}

TEST(WarpInspectorWindow, RealWindowUnderXvfb) {
  if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "xvfb-run is not installed (apt-get install xvfb xauth): skipping the real-window test";
  std::string shot = tempDir() + "/window.png";
  RunResult r = test::runUnderXvfb(
      std::string(PENUMBRA_BINARY) +
          " warp concentric-disk --gui --points 10 --grid-lines --frames 20 --window 960x640"
          " --print-layout --screenshot " +
          shot,
      1200);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.out.find("GLFW"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("panel histogram"), std::string::npos) << r.out;
  Image img = readPng(shot);
  EXPECT_EQ(img.width, 960);
  EXPECT_EQ(img.height, 640);
}
