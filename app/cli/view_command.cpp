// penumbra view: the interactive viewer (app/ui) in a GLFW window, or offscreen through OSMesa.
//
// Two executables are built from the same UI library: `penumbra` (GLFW + libGL) and
// `penumbra-offscreen` (OSMesa, no libGL: an executable must not link both, or gl* calls go to the
// wrong library). `penumbra view --offscreen`, and `penumbra view` on a machine without a display,
// re-execute the sibling penumbra-offscreen with the same options, so users see one command.
// This file is compiled into each executable (not into penumbra_cli, which the tests link without GL).
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "app/cli/commands.h"
#include "app/cli/display_server_option.h"
#include "app/cli/scene_options.h"
#include "app/platform/offscreen_exec.h"
#include "app/platform/platform.h"
#include "app/ui/id_audit.h"
#include "app/ui/monkey_driver.h"
#include "app/ui/viewer_app.h"
#include "core/math/error.h"

namespace penumbra::cli {

namespace {

struct ViewOptions {
  SceneOptions scene;
  bool offscreen = false;
  int frames = -1;
  std::string screenshot;
  bool bench = false;
  bool noWait = false;
  bool printLayout = false;
  bool openWarpInspector = false;
  int threads = 0;
  std::string compare;
  std::string window;  // WxH
  std::string view;    // colour | mis-light-share
  std::string reference;
  DisplayServerOption display;
  // Robustness harness (docs/viewer.md, "Robustness"); hidden options.
  std::int64_t monkeySeed = -1;  // >= 0: run the monkey with this seed
  std::string monkeyLog, monkeyReplay, monkeyOpen;
  double monkeyFrameLimit = 1.0;
  bool auditIds = false;
};

constexpr const char* kFallbackScreenshot = "penumbra-view.png";

// The viewer's image (R, G, B) as tev's "<scene> [<strategy>]": offered after every poll (sent when an
// update is due), and sent once more when the viewer closes. Compare mode streams its left side.
void streamToTev(net::TevStreamer& tev, const ui::ViewerController& c, bool last) {
  if (c.snapshotRestart() != c.restartCount()) return;  // the previous accumulation's image
  const std::string name = tevImageName(c.scene().path, c.settings().integrator);
  if (!last)
    tev.offer(name, c.snapshot());
  else if (c.snapshot().spp > 0)
    tev.send(net::TevFrame{name, c.snapshot().mean, Image()});
}

// Whether a program drives the viewer instead of a person (the monkey, the ID audit).
bool driven(const ViewOptions& o) {
  return o.monkeySeed >= 0 || !o.monkeyReplay.empty() || o.auditIds;
}

// This command's arguments for penumbra-offscreen.
std::vector<std::string> offscreenArgs(const ViewOptions& o) {
  std::vector<std::string> args = {"view"};
  if (!o.scene.scenePath.empty()) args.push_back(o.scene.scenePath);
  for (const std::string& s : o.scene.sets) args.insert(args.end(), {"--set", s});
  if (o.frames >= 0) args.insert(args.end(), {"--frames", std::to_string(o.frames)});
  if (!driven(o)) {
    args.insert(args.end(),
                {"--screenshot", o.screenshot.empty() && !o.bench ? kFallbackScreenshot : o.screenshot});
    if (args.back().empty()) args.resize(args.size() - 2);
  }
  if (o.bench) args.push_back("--bench");
  if (o.noWait) args.push_back("--no-wait");
  if (o.printLayout) args.push_back("--print-layout");
  if (o.openWarpInspector) args.push_back("--open-warp-inspector");
  if (o.threads > 0) args.insert(args.end(), {"--threads", std::to_string(o.threads)});
  if (!o.window.empty()) args.insert(args.end(), {"--window", o.window});
  if (!o.compare.empty()) args.insert(args.end(), {"--compare", o.compare});
  if (!o.view.empty()) args.insert(args.end(), {"--view", o.view});
  if (!o.reference.empty()) args.insert(args.end(), {"--reference", o.reference});
  if (!o.display.spec.empty()) args.insert(args.end(), {"--display-server", o.display.spec});
  if (o.monkeySeed >= 0) args.insert(args.end(), {"--monkey", std::to_string(o.monkeySeed)});
  if (!o.monkeyLog.empty()) args.insert(args.end(), {"--monkey-log", o.monkeyLog});
  if (!o.monkeyReplay.empty()) args.insert(args.end(), {"--monkey-replay", o.monkeyReplay});
  if (!o.monkeyOpen.empty()) args.insert(args.end(), {"--monkey-open", o.monkeyOpen});
  if (o.monkeySeed >= 0 || !o.monkeyReplay.empty())
    args.insert(args.end(), {"--monkey-frame-limit", std::to_string(o.monkeyFrameLimit)});
  if (o.auditIds) args.push_back("--audit-ids");
  return args;
}

// The command line that runs this monkey again (printed when it fails).
std::string replayCommand(const ViewOptions& o) {
  std::string line = platform::offscreenBinary();
  for (const std::string& a : offscreenArgs(o)) {
    const bool plain = !a.empty() && a.find_first_not_of(
                                         "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
                                         "._-+=/:,") == std::string::npos;
    line += " " + (plain ? a : "'" + a + "'");
  }
  return line;
}

int runView(ViewOptions o) {
  const bool offscreenBuild = platform::isOffscreenBuild();
  platform::runOffscreenUnlessWindowed("penumbra view", o.offscreen || driven(o),
                                       o.screenshot.empty() ? kFallbackScreenshot : o.screenshot,
                                       [&] { return offscreenArgs(o); });

  std::optional<net::DisplayServer> displayServer = o.display.resolve();  // a bad host exits with 2
  const auto loadStart = std::chrono::steady_clock::now();
  LoadedScene loaded = o.scene.load();  // throws penumbra::Error (exit code 2) on a bad scene
  const double loadSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - loadStart).count();
  ui::ViewerOptions vo;
  vo.bench = o.bench;
  vo.threads = o.threads;
  vo.printLayout = o.printLayout;
  vo.openWarpInspector = o.openWarpInspector;
  vo.compare = o.compare;
  vo.lightShareView = o.view == "mis-light-share";
  vo.reference = o.reference;
  vo.screenshot = o.screenshot;
  if (offscreenBuild && vo.screenshot.empty() && !o.bench) vo.screenshot = kFallbackScreenshot;
  vo.frames = o.frames >= 0 ? o.frames : (offscreenBuild ? 3 : 0);
  vo.waitForTarget = offscreenBuild && !o.noWait && !vo.screenshot.empty();
  if (!o.window.empty()) {
    if (std::sscanf(o.window.c_str(), "%dx%d", &vo.windowWidth, &vo.windowHeight) != 2 ||
        vo.windowWidth < 64 || vo.windowHeight < 64)
      throw Error("--window " + o.window + ": expected WIDTHxHEIGHT, e.g. 1280x800");
  }
  std::unique_ptr<net::TevStreamer> tev = openStream(displayServer);
  if (tev) vo.onSnapshot = [&tev](const ui::ViewerController& c, bool last) { streamToTev(*tev, c, last); };
  vo.loadSeconds = loadSeconds;
  if (o.auditIds) {
    vo.driver = ui::makeIdAuditDriver();
  } else if (driven(o)) {
    ui::MonkeyOptions mo;
    mo.seed = std::uint64_t(std::max<std::int64_t>(o.monkeySeed, 0));
    mo.frames = o.frames;  // -1: the replayed log's, else 1000
    mo.frameLimitSeconds = o.monkeyFrameLimit;
    mo.logPath = o.monkeyLog;
    mo.replayPath = o.monkeyReplay;
    mo.openScene = o.monkeyOpen;
    mo.replayCommand = replayCommand(o);
    vo.driver = ui::makeMonkeyDriver(mo);
  }
  return ui::runViewer(std::move(loaded), o.scene.overrides(), vo);
}

}  // namespace

void addViewCommand(CLI::App& app, int& exitCode) {
  auto opts = std::make_shared<ViewOptions>();
  CLI::App* cmd =
      app.add_subcommand("view", "Open the interactive progressive viewer (default: the built-in scene)");
  opts->scene.addTo(*cmd, /*sceneRequired=*/false);
  cmd->add_flag("--offscreen", opts->offscreen,
                "Render the UI offscreen (OSMesa) instead of opening a window");
  cmd->add_option("--frames", opts->frames, "Stop after N UI frames (offscreen default: 3)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--screenshot", opts->screenshot, "Write the last frame, panels included, to this PNG");
  cmd->add_flag("--no-wait", opts->noWait,
                "Offscreen: take the screenshot without waiting for the target spp");
  cmd->add_flag("--bench", opts->bench,
                "Measure UI frame time, restart latency and throughput lost to the UI");
  cmd->add_option("--threads", opts->threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--compare", opts->compare,
                  "Start in compare mode: this measure (e.g. solid-angle, mis) or strategy (area-bvh) right "
                  "of the divider, "
                  "the scene's on the left, each with half of the threads");
  cmd->add_option("--window", opts->window, "Window / offscreen buffer size, e.g. 1280x800");
  cmd->add_option("--view", opts->view,
                  "Start in this view: colour (default) or mis-light-share (a mis strategy: the light "
                  "technique's share of each pixel, false colour)")
      ->check(CLI::IsMember({"colour", "mis-light-share"}));
  cmd->add_option("--reference", opts->reference,
                  "Load this EXR/PFM as the Convergence panel's reference (its size must be the image's); "
                  "a file that cannot be used is shown there, the viewer runs on");
  opts->display.addTo(*cmd);
  cmd->add_flag("--print-layout", opts->printLayout, "Print where the image is drawn (for tests)")->group("");
  cmd->add_flag("--open-warp-inspector", opts->openWarpInspector,
                "Start with the warp inspector open (screenshots)")
      ->group("");
  // The robustness harness (docs/viewer.md, "Robustness"): offscreen only, for tests and replays.
  cmd->add_option("--monkey", opts->monkeySeed,
                  "Drive the UI with seeded random input for --frames frames (default 1000) and check it")
      ->check(CLI::NonNegativeNumber)
      ->group("");
  cmd->add_option("--monkey-log", opts->monkeyLog, "Write the monkey's input, one line per frame")->group("");
  cmd->add_option("--monkey-replay", opts->monkeyReplay, "Play back a --monkey-log instead of random input")
      ->group("");
  cmd->add_option("--monkey-open", opts->monkeyOpen, "Open this scene at the monkey's first frame")
      ->group("");
  cmd->add_option("--monkey-frame-limit", opts->monkeyFrameLimit, "Longest frame in seconds (default 1)")
      ->check(CLI::PositiveNumber)
      ->group("");
  cmd->add_flag("--audit-ids", opts->auditIds,
                "Draw every panel state, click every widget, fail on two widgets of a window with one ID")
      ->group("");
  cmd->callback([opts, &exitCode] { exitCode = runView(*opts); });
}

}  // namespace penumbra::cli
