#include "app/ui/monkey_driver.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <vector>

#include <imgui.h>

#include "app/ui/input_frame.h"
#include "app/ui/item_log.h"
#include "app/ui/monkey.h"
#include "core/render/strategy_axes.h"

namespace penumbra::ui {

namespace {

enum class Phase { Plain, Compare, WarpInspector, LightShare };
constexpr int kPhases = 4;
const char* const kPhaseNames[kPhases] = {"plain", "compare", "warp inspector", "MIS light share"};

// What an abort (an ImGui assert) or a crash prints, formatted beforehand: the handler only writes.
struct CrashReport {
  static constexpr int kLines = 24;
  char lines[kLines][240] = {};
  long written = 0;
  char where[256] = "monkey: died before the first frame\n";
  char replay[4096] = "";
} gCrash;

void writeAll(const char* s) {
  for (size_t n = std::strlen(s); n > 0;) {
    ssize_t w = ::write(STDERR_FILENO, s, n);
    if (w <= 0) return;
    s += w, n -= size_t(w);
  }
}

void onFatalSignal(int sig) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "\nmonkey: FAILED: signal %d (%s)\n", sig,
                sig == SIGABRT ? "abort" : "crash");
  writeAll(buf);
  writeAll(gCrash.where);
  writeAll("monkey: the last inputs (frame x y buttons wheel key mods text):\n");
  for (long i = std::max(0L, gCrash.written - CrashReport::kLines); i < gCrash.written; ++i)
    writeAll(gCrash.lines[i % CrashReport::kLines]);
  writeAll(gCrash.replay);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

#if defined(__SANITIZE_ADDRESS__)
#define PENUMBRA_MONKEY_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PENUMBRA_MONKEY_ASAN 1
#endif
#endif

void installCrashHandlers() {
  std::signal(SIGABRT, onFatalSignal);  // ImGui's asserts, std::terminate
#ifndef PENUMBRA_MONKEY_ASAN            // AddressSanitizer reports crashes itself, with a stack
  std::signal(SIGSEGV, onFatalSignal);
  std::signal(SIGBUS, onFatalSignal);
  std::signal(SIGFPE, onFatalSignal);
#endif
}

// The first non-finite value of an image: its count, and where the first one is.
bool allFinite(const Image& img, std::string& what, const char* name) {
  size_t bad = 0, first = 0;
  for (size_t i = 0; i < img.rgb.size(); ++i)
    if (!std::isfinite(img.rgb[i]) && bad++ == 0) first = i;
  if (bad == 0) return true;
  const size_t pixel = first / 3;
  char buf[200];
  std::snprintf(buf, sizeof buf, "%s has %zu NaN/Inf values, the first at pixel (%zu, %zu)", name, bad,
                pixel % size_t(std::max(img.width, 1)), pixel / size_t(std::max(img.width, 1)));
  what = buf;
  return false;
}

class MonkeyDriver final : public FrameDriver {
 public:
  explicit MonkeyDriver(const MonkeyOptions& o) : o_(o), monkey_(o.seed) {
    setActiveItemLog(&items_);
    int loggedFrames = -1;  // the "# frames N" line of a replayed log: its run's phases
    if (!o_.replayPath.empty()) {
      std::ifstream in(o_.replayPath);
      if (!in) fail(-1, "cannot read the input log " + o_.replayPath);
      for (std::string line; std::getline(in, line);) {
        if (line.rfind("# frames ", 0) == 0) loggedFrames = std::atoi(line.c_str() + 9);
        if (line.empty() || line[0] == '#') continue;
        size_t space = line.find(' ');
        InputFrame f;
        if (space == std::string::npos || !parseInput(line.substr(space + 1), f)) {
          fail(-1, o_.replayPath + ": not an input line: " + line);
          break;
        }
        replay_.push_back(f);
      }
    }
    if (o_.frames < 0) o_.frames = loggedFrames > 0 ? loggedFrames : 1000;
    if (!o_.logPath.empty()) {
      log_ = std::fopen(o_.logPath.c_str(), "w");
      if (!log_) std::fprintf(stderr, "monkey: cannot write the input log %s\n", o_.logPath.c_str());
      if (log_) std::fprintf(log_, "# frames %d seed %llu\n", o_.frames, (unsigned long long)o_.seed);
    }
    std::snprintf(gCrash.replay, sizeof gCrash.replay, "monkey: replay: %s\n", o_.replayCommand.c_str());
    installCrashHandlers();
  }
  ~MonkeyDriver() override {
    setActiveItemLog(nullptr);
    if (log_) std::fclose(log_);
  }

  bool beforeFrame(int index, DrivenViewer& v) override {
    if (failed_ || index >= o_.frames) return false;
    if (!replay_.empty() || !o_.replayPath.empty()) {
      if (index >= int(replay_.size())) return false;
    }
    ViewerController& c = v.controller();
    if (index == 0) {
      installIdentityKeyMap(ImGui::GetIO());
      if (!o_.openScene.empty()) c.openSceneAsync(o_.openScene);
    }
    const int phase = std::min(kPhases - 1, int(int64_t(index) * kPhases / std::max(o_.frames, 1)));
    if (index == 0 || phase != phase_) enterPhase(Phase(phase), v, index);

    int w = 0, h = 0;
    v.windowSize(w, h);
    MonkeyView view;
    view.width = float(w), view.height = float(h);
    view.items = items_.items();
    view.paths = c.siblingScenes();
    for (const std::string& r : c.recentFiles()) view.paths.push_back(r);
    const InputFrame in = o_.replayPath.empty() ? monkey_.next(view) : replay_[size_t(index)];
    items_.beginFrame();
    applyInput(in, ImGui::GetIO());

    const std::string line = std::to_string(index) + " " + formatInput(in);
    if (log_) {
      std::fprintf(log_, "%s\n", line.c_str());
      std::fflush(log_);
    }
    std::snprintf(gCrash.lines[gCrash.written % CrashReport::kLines], sizeof gCrash.lines[0], "  %s\n",
                  line.c_str());
    ++gCrash.written;
    std::snprintf(gCrash.where, sizeof gCrash.where, "monkey: at frame %d of %d (%s, phase %s)\n", index,
                  o_.frames, runName().c_str(), kPhaseNames[phase_]);
    return true;
  }

  bool afterFrame(int index, DrivenViewer& v, double seconds) override {
    ++framesRun_;
    if (seconds > maxSeconds_) maxSeconds_ = seconds, slowestFrame_ = index;
    if (index == 0 && items_.totalAdded() == 0)
      return fail(index,
                  "no ImGui items were recorded: this binary lacks the item hook "
                  "(app/ui/imgui_item_hook.cpp; penumbra-offscreen links it)");
    for (const DuplicateId& d : items_.duplicates())
      return fail(index, "duplicate widget ID: " + d.describe());
    if (seconds > o_.frameLimitSeconds) {
      char buf[160];
      std::snprintf(buf, sizeof buf,
                    "the frame took %.3f s (limit %.3g s; scene loading and waiting for a CPU excluded), ",
                    seconds, o_.frameLimitSeconds);
      return fail(index, buf + v.lastFrameBreakdown());
    }
    const ViewerController& c = v.controller();
    std::string what;
    if (c.snapshotSerial() != seenSerial_) {
      seenSerial_ = c.snapshotSerial();
      if (!allFinite(c.snapshot().mean, what, "the displayed image") ||
          !allFinite(c.snapshot().standardError, what, "the displayed standard error"))
        return fail(index, what);
    }
    if (c.compareSnapshotSerial() != seenCompareSerial_) {
      seenCompareSerial_ = c.compareSnapshotSerial();
      if (!allFinite(c.compareSnapshot().mean, what, "the compare side's displayed image"))
        return fail(index, what);
    }
    if (!stateFinite(c, what)) return fail(index, "a viewer setting is not finite: " + what);
    return true;
  }

  void frameThrew(int index, const std::string& what) override { fail(index, "exception: " + what); }

  int exitCode() const override {
    if (failed_) return 1;
    std::printf("monkey: passed %d frames (%s), slowest frame %.3f s (frame %d)\n", framesRun_,
                runName().c_str(), maxSeconds_, slowestFrame_);
    std::fflush(stdout);
    return 0;
  }

 private:
  std::string runName() const {
    return o_.replayPath.empty() ? "seed " + std::to_string(o_.seed) : "replay of " + o_.replayPath;
  }

  bool fail(int index, const std::string& why) {
    if (failed_) return false;
    failed_ = true;
    std::fprintf(stderr, "monkey: FAILED at frame %d of %d (%s, phase %s): %s\n", index, o_.frames,
                 runName().c_str(), kPhaseNames[phase_], why.c_str());
    std::fprintf(stderr, "monkey: the last inputs (frame x y buttons wheel key mods text):\n");
    for (long i = std::max(0L, gCrash.written - CrashReport::kLines); i < gCrash.written; ++i)
      std::fputs(gCrash.lines[i % CrashReport::kLines], stderr);
    std::fprintf(stderr, "%s", gCrash.replay);
    return false;
  }

  // Starts a phase in its mode, switching the strategy where the scene's own cannot show the mode.
  void enterPhase(Phase p, DrivenViewer& v, int index) {
    phase_ = int(p);
    ViewerController& c = v.controller();
    v.setWarpInspectorOpen(p == Phase::WarpInspector);
    if (p != Phase::LightShare && c.lightShareView()) c.setLightShareView(false);
    if (p != Phase::Compare && c.compareEnabled()) c.setCompare(false);
    std::string note;
    if (p == Phase::Compare) {
      for (const IntegratorTypeRow& t : kIntegratorTypes) {
        if (c.compareOffered()) break;
        c.setStrategy(applicableStrategy(integratorOfType(t.type), c.sceneHasAreaLights()));
      }
      if (!c.compareOffered())
        note = " (not offered: no strategy of this scene has another to compare with)";
      else
        c.setCompare(true);
    } else if (p == Phase::LightShare) {
      for (const IntegratorDesc& s : everyStrategyOfType(integratorOfType(IntegratorType::Direct))) {
        if (c.lightShareOffered()) break;
        if (offersLightShare(s) && strategyApplies(s, c.sceneHasAreaLights())) c.setStrategy(s);
      }
      if (c.lightShareOffered())
        c.setLightShareView(true);
      else
        note = " (not offered: the scene has no area light for a mis strategy)";
    }
    std::printf("monkey: frame %d: phase %s, %s%s\n", index, kPhaseNames[phase_],
                strategyLabel(c.settings().integrator).c_str(), note.c_str());
    std::fflush(stdout);
  }

  static bool stateFinite(const ViewerController& c, std::string& what) {
    auto check = [&what](const char* name, double v) {
      if (std::isfinite(v)) return true;
      what = std::string(name) + " = " + std::to_string(v);
      return false;
    };
    const CameraDesc& cam = c.settings().camera;
    for (int col = 0; col < 4; ++col)
      for (int row = 0; row < 4; ++row)
        if (!check("camera.toWorld", cam.toWorld[col][row])) return false;
    const OrbitCamera& o = c.orbitCamera();
    const DisplaySettings& d = c.display;
    return check("camera.fov", cam.fovDegrees) && check("orbit distance", o.distance) &&
           check("orbit target x", o.target.x) && check("orbit target y", o.target.y) &&
           check("orbit target z", o.target.z) && check("exposure", d.exposure) && check("zoom", d.zoom) &&
           check("pan x", d.panX) && check("pan y", d.panY) && check("compare divider", d.compareDivider) &&
           check("time budget", c.limits().seconds);
  }

  MonkeyOptions o_;
  Monkey monkey_;
  ItemLog items_;
  std::vector<InputFrame> replay_;
  std::FILE* log_ = nullptr;
  int phase_ = 0;
  bool failed_ = false;
  int framesRun_ = 0;
  double maxSeconds_ = 0;
  int slowestFrame_ = 0;
  uint64_t seenSerial_ = ~0ull, seenCompareSerial_ = ~0ull;
};

}  // namespace

std::shared_ptr<FrameDriver> makeMonkeyDriver(const MonkeyOptions& options) {
  return std::make_shared<MonkeyDriver>(options);
}

}  // namespace penumbra::ui
