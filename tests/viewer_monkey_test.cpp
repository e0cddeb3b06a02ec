// The viewer's robustness tests (docs/viewer.md, "Robustness"), each in a child penumbra-offscreen so
// that an abort (an ImGui assert) or a crash fails the test with its report instead of ending ctest:
//  - ViewerMonkey: the monkey (`view --monkey`) on every scene under scenes/ and the built-in one,
//    through the plain view, compare mode, the warp inspector and the MIS light-share view.
//    PENUMBRA_MONKEY_FRAMES (frames per scene), PENUMBRA_MONKEY_SEED (added to each scene's seed)
//    and PENUMBRA_MONKEY_FRAME_LIMIT (seconds) override the defaults, PENUMBRA_MONKEY_VIEWER the
//    viewer binary; tools/monkey runs 10,000 frames per scene. Each case runs on its own copy of scenes/.
//  - ViewerWidgetIds: the widget-ID audit (`view --audit-ids`) on one scene of each kind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/run_command.h"

namespace fs = std::filesystem;
using namespace penumbra;

namespace {

#ifdef PENUMBRA_SANITIZED_BUILD
// Under ASan+UBSan (tools/sanitize asan) the UI code runs ~3x slower: fewer frames, a longer limit.
constexpr int kDefaultFrames = 16;
constexpr double kDefaultFrameLimit = 10.0;
#else
constexpr int kDefaultFrames = 48;
constexpr double kDefaultFrameLimit = 1.0;
#endif

const std::string kBuiltIn = "built-in";

// Scenes too heavy for thousands of frames as they are, and what the monkey changes (the test says it).
const std::pair<const char*, const char*> kSceneOverrides[] = {
    // 1.3 M triangles: seconds per load and per reload; 5 subdivisions keep the shape (20 k triangles).
    {"standin/rock-ao.xml", "--set shape.subdivisions=5"},
};

std::string scenesDir() {
  return std::string(PENUMBRA_SOURCE_DIR) + "/scenes";
}

// Every .xml under scenes/, relative to it, sorted; then the built-in scene.
std::vector<std::string> monkeyScenes() {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(scenesDir()))
    if (e.is_regular_file() && e.path().extension() == ".xml")
      out.push_back(fs::relative(e.path(), scenesDir()).string());
  std::sort(out.begin(), out.end());
  out.push_back(kBuiltIn);
  return out;
}

std::string testName(const std::string& scene) {
  std::string n;
  for (char c : scene) n += std::isalnum((unsigned char)c) ? c : '_';
  return n.substr(0, n.size() > 4 && n.substr(n.size() - 4) == "_xml" ? n.size() - 4 : n.size());
}

// The viewer binary under test: PENUMBRA_MONKEY_VIEWER (tools/monkey runs a copy, so that a rebuild
// during a long run does not change what runs), else the one this build made.
std::string viewerBinary() {
  const char* v = std::getenv("PENUMBRA_MONKEY_VIEWER");
  return v && *v ? v : PENUMBRA_OFFSCREEN_BINARY;
}

double envNumber(const char* name, double fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::atof(v) : fallback;
}

// A fresh working directory for the child, holding its own copy of scenes/: the monkey saves images
// and scenes where it stands and, through paths it copies from the Scene panel and pastes into the
// save fields, over the scenes it opened, so it must never see the source tree's.
struct WorkDir {
  fs::path path;
  explicit WorkDir(const std::string& name) {
    path = fs::temp_directory_path() / ("penumbra-monkey-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(path);
    fs::create_directories(path);
    fs::copy(scenesDir(), scenes(), fs::copy_options::recursive);
  }
  fs::path scenes() const { return path / "scenes"; }
  // The scene's copy in this directory; "" for the built-in scene.
  std::string scene(const std::string& relative) const {
    return relative == kBuiltIn ? "" : (scenes() / relative).string();
  }
  ~WorkDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

std::string tail(const std::string& text, size_t lines) {
  size_t pos = text.size();
  for (size_t n = 0; n <= lines && pos != std::string::npos && pos > 0; ++n) pos = text.rfind('\n', pos - 1);
  return pos == std::string::npos ? text : text.substr(pos + 1);
}

std::string readFile(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class ViewerMonkey : public testing::TestWithParam<std::string> {};

TEST_P(ViewerMonkey, SurvivesRandomInputInEveryMode) {
  const std::string scene = GetParam();
  const std::vector<std::string> all = monkeyScenes();
  const size_t index = size_t(std::find(all.begin(), all.end(), scene) - all.begin());
  const int frames = int(envNumber("PENUMBRA_MONKEY_FRAMES", kDefaultFrames));
  const double limit = envNumber("PENUMBRA_MONKEY_FRAME_LIMIT", kDefaultFrameLimit);
  const unsigned long long seed =
      1000 * (unsigned long long)index + (unsigned long long)envNumber("PENUMBRA_MONKEY_SEED", 1);
  const char* window = index % 2 ? "1920x1080" : "1280x800";  // the two screens
  WorkDir dir(testName(scene));
  const std::string log = (dir.path / "monkey-input.log").string();
  const std::string path = dir.scene(scene);
  std::string sets;
  for (const auto& [name, set] : kSceneOverrides)
    if (scene == name) {
      sets = std::string(" ") + set;
      std::printf("monkey: %s runs with%s\n", name, set);
    }
  // A hang is killed: generous for a loaded 2-core machine (a frame takes ~10-50 ms there).
  const int timeoutSeconds = 120 + int(frames * std::max(limit, 1.0) * 0.5);
  std::string viewer;  // the viewer's command line without the monkey's own options
  auto monkeyCommand = [&](const std::string& scenePath, const std::string& extra) {
    viewer = viewerBinary() + " view " + scenePath + sets + " --window " + window + " --frames " +
             std::to_string(frames) + " --monkey-frame-limit " + std::to_string(limit) + extra;
    return viewer + " --monkey " + std::to_string(seed) + " --monkey-log " + log;
  };
  std::string command = monkeyCommand(path, "");
  auto run = [&](const std::string& cmd) {
    return test::runCommand("cd " + dir.path.string() + " && timeout -s KILL " +
                            std::to_string(timeoutSeconds) + " " + cmd);
  };
  test::CommandResult r = run(command);
  if (r.exitCode == 2 && r.out.find("monkey:") == std::string::npos) {
    // The scene does not load (scenes/stiff/bad-*): the command line says so, naming the file...
    EXPECT_NE(r.out.find(fs::path(scene).filename().string()), std::string::npos) << r.out;
    std::printf("monkey: %s does not load (%s); opening it from the built-in scene's Scene panel\n",
                scene.c_str(), tail(r.out, 1).c_str());
    // ...and the viewer that opens it keeps running the last good scene under the monkey.
    command = monkeyCommand("", " --monkey-open " + path);
    r = run(command);
  }
  const bool passed = r.exitCode == 0 && r.out.find("monkey: passed") != std::string::npos;
  // The input log outlives the working directory, for an exact replay.
  const fs::path kept = fs::temp_directory_path() /
                        ("penumbra-monkey-" + testName(scene) + "-" + std::to_string(seed) + ".log");
  std::error_code ec;
  if (!passed) fs::copy_file(log, kept, fs::copy_options::overwrite_existing, ec);
  EXPECT_TRUE(passed) << "exit code " << r.exitCode
                      << (r.exitCode == 137
                              ? " (killed after " + std::to_string(timeoutSeconds) + " s: a hang)"
                              : std::string())
                      << "\n--- output (last 60 lines):\n"
                      << tail(r.out, 60) << "\n--- input log (last 20 frames):\n"
                      << tail(readFile(log), 20) << "\n--- replay (from an empty directory):\n  " << command
                      << "\n--- replay of exactly this input:\n  " << viewer << " --monkey-replay "
                      << kept.string();
  if (passed) std::printf("%s", tail(r.out, 1).c_str());
}

INSTANTIATE_TEST_SUITE_P(Scenes, ViewerMonkey, testing::ValuesIn(monkeyScenes()),
                         [](const testing::TestParamInfo<std::string>& info) {
                           return testName(info.param);
                         });

// One scene of each kind the panels change with: the built-in one, area lights with mis, point
// lights only, ambient occlusion, a closed-form reference (the Convergence panel's plot), and a mesh.
// Under ASan+UBSan only the built-in one (its ~1,000 frames take minutes there; IDs do not depend on
// the build).
const std::vector<std::string> kAuditScenes = {
#ifndef PENUMBRA_SANITIZED_BUILD
    "mis/two-lights.xml",
    "hw1/Tests/sphere-point.xml",
    "hw2/Tests/sphere-ao.xml",
    "analytic/plane-sphere-light.xml",
    "hw0/Tests/sphere-mesh.xml",
#endif
    "built-in"};

class ViewerWidgetIds : public testing::TestWithParam<std::string> {};

TEST_P(ViewerWidgetIds, NoWindowHasTwoWidgetsWithOneId) {
  const std::string scene = GetParam();
  WorkDir dir("audit-" + testName(scene));
  const std::string command = viewerBinary() + " view " + dir.scene(scene) +
                              " --set camera.width=96 --set camera.height=72 --window 1280x800 --audit-ids";
  test::CommandResult r = test::runCommand("cd " + dir.path.string() + " && timeout -s KILL 600 " + command);
  EXPECT_EQ(r.exitCode, 0) << tail(r.out, 60) << "\n--- command:\n  " << command;
  EXPECT_NE(r.out.find("audit:"), std::string::npos) << r.out;
  std::printf("%s", tail(r.out, 1).c_str());
}

INSTANTIATE_TEST_SUITE_P(Scenes, ViewerWidgetIds, testing::ValuesIn(kAuditScenes),
                         [](const testing::TestParamInfo<std::string>& info) {
                           return testName(info.param);
                         });

}  // namespace
