#include "app/ui/viewer_bench.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>

#include "app/ui/ui_clock.h"
#include "core/analysis/order_statistics.h"
#include "core/render/cpu_clock.h"

namespace penumbra::ui {

namespace {

constexpr const char* kStageNames[kFrameStages] = {"ImGui build (NewFrame..Render)", "tone map + upload",
                                                   "panel fill, background, image copy", "ImGui draw",
                                                   "present (swap / finish)"};

}  // namespace

void FrameStageTimer::begin() {
  wall_ = Clock::now();
  cpuMs_ = processCpuSeconds() * 1e3;
}

void FrameStageTimer::end(FrameStage stage) {
  glFinish();
  const double cpu = processCpuSeconds() * 1e3;
  wallMs[stage] += msSince(wall_);
  cpuMs[stage] += cpu - cpuMs_;
  wall_ = Clock::now();
  cpuMs_ = cpu;
}

namespace {

// CPU time of the viewer's own threads (Linux /proc; ms): the UI thread is the main thread, the GL
// rasteriser's threads are Mesa's "llvmpipe-N"; the rest are the render workers, which come and go
// with every restart.
struct CpuSplit {
  double ui = 0, gl = 0;
};
CpuSplit cpuSplit() {
  CpuSplit c;
  const std::string self = std::to_string(::getpid());
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    std::ifstream commFile(task.path() / "comm"), stat(task.path() / "schedstat");
    std::string comm;
    double ns = 0;
    if (!std::getline(commFile, comm) || !(stat >> ns)) continue;
    if (task.path().filename() == self)
      c.ui += ns * 1e-6;
    else if (comm.rfind("llvmpipe", 0) == 0)
      c.gl += ns * 1e-6;
  }
  return c;
}

// One stretch of rendering: the engine's throughput, and the time of every UI frame drawn.
struct Phase {
  std::vector<double> frameMs;
  double seconds = 0, samplesPerSecond = 0, uiCpuMs = 0, glCpuMs = 0;
};

// Throughput from the pass boundaries seen during a phase: samples of the passes completed between the
// second boundary and the last one, over the time between them (the first pass after a restart also
// carries the preview; counting whole passes over a fixed time would quantise by a pass, ~6 %).
class PassClock {
 public:
  // Pass boundaries are timed by the engine's clock when they happen, not when this loop sees them
  // (a viewer that sleeps between frames sees them late).
  void tick(const RenderProgress& p) {
    if (p.spp == spp_) return;
    spp_ = p.spp;
    if (++boundaries_ == 2) first_ = p.passSeconds, firstSamples_ = p.samples;
    if (boundaries_ >= 2) last_ = p.passSeconds, lastSamples_ = p.samples;
  }
  double samplesPerSecond() const {
    double s = last_ - first_;
    return s > 0 ? double(lastSamples_ - firstSamples_) / s : 0.0;
  }

 private:
  uint32_t spp_ = 0;
  int boundaries_ = 0;
  double first_ = 0, last_ = 0;
  uint64_t firstSamples_ = 0, lastSamples_ = 0;
};

enum class Mode { EngineAlone, Watching, Redrawing };

Phase runPhase(BenchViewer& app, ViewerController& c, double seconds, Mode mode) {
  Phase r;
  c.start();
  PassClock passes;
  CpuSplit c0 = cpuSplit();
  auto t0 = Clock::now();
  if (mode == Mode::EngineAlone) {
    // Only looks at the pass counter every 5 ms (negligible next to the UI's frames).
    while (msSince(t0) < seconds * 1000) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      passes.tick(c.progress());
    }
  } else {
    // Redrawing: the exposure changes before every frame, as while its slider is dragged, so every
    // frame tone maps the image again and redraws the panels (a display-only change: no restart).
    // The loop wakes on every snapshot, i.e. at every pass boundary, where the clock ticks.
    const float exposure = c.display.exposure;
    uint64_t frames = app.framesDrawn();
    app.run(
        [&] {
          passes.tick(c.progress());
          if (app.framesDrawn() != frames) {
            frames = app.framesDrawn();
            r.frameMs.push_back(app.lastFrameMs());
            if (mode == Mode::Redrawing) c.display.exposure = exposure + (frames % 2 ? 0.25f : -0.25f);
          }
          return msSince(t0) >= seconds * 1000;
        },
        mode == Mode::Redrawing);
    c.display.exposure = exposure;
  }
  r.seconds = msSince(t0) * 1e-3;
  r.samplesPerSecond = passes.samplesPerSecond();
  CpuSplit c1 = cpuSplit();
  r.uiCpuMs = c1.ui - c0.ui;
  r.glCpuMs = c1.gl - c0.gl;
  return r;
}

// `penumbra view --bench`. Rounds of three phases on the same accumulation settings: the engine alone
// (what `penumbra render` does), the viewer's own loop watching it (no input: it draws when a pass
// arrives), and the loop redrawing every frame at the display rate with the exposure changing before
// each (as while its slider is dragged: every frame tone maps the image and redraws the panels);
// each round compares its phases, so a load change on a shared machine skews one round, not the
// medians. Then restart latency, then where a frame's time goes.
}  // namespace

int runViewerBench(platform::Platform& p, ViewerController& c, BenchViewer& app) {
  const RenderSettings& s = c.settings();
  const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
  std::printf("bench: %s, %dx%d, %s, %d worker threads (nice %d), %d cores, %s, tone mapping on the %s\n",
              p.name(), s.camera.width, s.camera.height, strategyLabel(s.integrator).c_str(),
              c.engine().threadCount(), kViewerWorkerNice, cores, p.glRenderer().c_str(),
              app.tonemapper() == Tonemapper::Cpu ? "CPU (software GL)" : "GPU (display.frag)");
  RenderLimits endless;
  c.setLimits(endless);
  const int rounds = 5;
  const double seconds = 3.0;
  std::vector<double> alone, watchLost, busyLost, watchFrames, busyFrames, watchRate, busyRate;
  std::vector<double> watchUi, busyUi, watchGl, busyGl;
  for (int i = 0; i < rounds; ++i) {
    Phase a = runPhase(app, c, seconds, Mode::EngineAlone);
    Phase w = runPhase(app, c, seconds, Mode::Watching);
    Phase b = runPhase(app, c, seconds, Mode::Redrawing);
    alone.push_back(a.samplesPerSecond);
    watchLost.push_back(100.0 * (1.0 - w.samplesPerSecond / std::max(a.samplesPerSecond, 1e-9)));
    busyLost.push_back(100.0 * (1.0 - b.samplesPerSecond / std::max(a.samplesPerSecond, 1e-9)));
    watchFrames.insert(watchFrames.end(), w.frameMs.begin(), w.frameMs.end());
    busyFrames.insert(busyFrames.end(), b.frameMs.begin(), b.frameMs.end());
    watchRate.push_back(double(w.frameMs.size()) / w.seconds);
    busyRate.push_back(double(b.frameMs.size()) / b.seconds);
    // CPU share of the cores: UI thread, and GL rasteriser threads.
    watchUi.push_back(100.0 * w.uiCpuMs / (w.seconds * 1e3 * cores));
    watchGl.push_back(100.0 * w.glCpuMs / (w.seconds * 1e3 * cores));
    busyUi.push_back(100.0 * b.uiCpuMs / (b.seconds * 1e3 * cores));
    busyGl.push_back(100.0 * b.glCpuMs / (b.seconds * 1e3 * cores));
  }

  // Restart latency: a control change (the seed) in the middle of an accumulation, until a frame
  // showing the new estimate (the engine's preview) is presented, and until its first full pass is.
  std::vector<double> latency, previewEngine, fullPass, handled;
  for (int i = 0; i < 10; ++i) {
    auto w0 = Clock::now();
    app.run([&] { return msSince(w0) >= 150 + 37 * i; }, false);  // a different phase of the pass each time
    RenderSettings next = c.settings();
    next.seed += 1;
    auto r0 = Clock::now();
    c.setSettings(next);
    handled.push_back(msSince(r0));
    const uint64_t restart = c.restartCount();
    double shown = -1;
    app.run(
        [&] {
          if (shown < 0 && app.shownRestart() == restart) {
            shown = msSince(r0);
            if (c.snapshot().spp == 0) previewEngine.push_back(c.snapshot().seconds * 1e3);
          }
          return (app.shownRestart() == restart && c.snapshot().spp >= 1) || msSince(r0) > 10000;
        },
        false);
    latency.push_back(shown < 0 ? msSince(r0) : shown);
    fullPass.push_back(msSince(r0));
  }

  // Where a frame's time goes: engine paused (so the CPU time is the UI's and GL's alone), every
  // frame tone mapping the image as a frame with a new snapshot does, glFinish after each stage.
  c.setPaused(true);
  FrameStageTimer stages;
  app.timeStages(&stages);
  const int breakdownFrames = 100;
  for (int i = 0; i < breakdownFrames; ++i) {
    app.forceTonemap();
    app.frame();
  }
  app.timeStages(nullptr);
  c.setPaused(false);

  std::printf("bench: engine alone %.3f M samples/s (median of %d rounds of %.1f s per phase)\n",
              median(alone) * 1e-6, rounds, seconds);
  std::printf(
      "bench: watching the accumulation (event-driven, no input): %.1f frames/s drawn, frame time median "
      "%.2f ms, p90 %.2f ms; CPU: UI thread %.1f %% + GL threads %.1f %% of the cores; throughput %.1f %% "
      "lost to the UI\n",
      median(watchRate), median(watchFrames), percentile(watchFrames, 0.9), median(watchUi), median(watchGl),
      median(watchLost));
  std::printf(
      "bench: dragging the exposure (a new tone mapping every frame, paced to 60 Hz): %.1f frames/s drawn, "
      "frame time median %.2f ms (%.0f "
      "fps), p90 %.2f ms; CPU: UI thread %.1f %% + GL threads %.1f %% of the cores; throughput %.1f %% lost "
      "to the UI\n",
      median(busyRate), median(busyFrames), 1000.0 / std::max(median(busyFrames), 1e-9),
      percentile(busyFrames, 0.9), median(busyUi), median(busyGl), median(busyLost));
  std::printf(
      "bench: restart latency (control change -> first frame of the new estimate on screen) median %.1f ms, "
      "max %.1f ms (the change itself: cancel and restart %.1f ms; the engine's preview published %.1f ms "
      "after the restart; medians)\n",
      median(latency), *std::max_element(latency.begin(), latency.end()), median(handled),
      median(previewEngine));
  std::printf("bench: control change -> first full pass on screen: median %.1f ms\n", median(fullPass));
  std::printf(
      "bench: frame breakdown (engine paused, image re-tone-mapped every frame, glFinish per part):\n");
  for (int i = 0; i < kFrameStages; ++i)
    std::printf("bench:   %-32s %6.2f ms wall %6.2f ms CPU\n", kStageNames[i],
                stages.wallMs[i] / breakdownFrames, stages.cpuMs[i] / breakdownFrames);
  double frameMs = std::max(median(watchFrames), median(busyFrames));
  std::printf(
      "bench: targets: >= 60 fps (frame time <= 16.7 ms): %s; <= 50 ms restart latency: %s; <= 10 %% lost: "
      "%s while watching, %s while dragging the exposure\n",
      frameMs <= 1000.0 / 60 ? "met" : "NOT met", median(latency) <= 50 ? "met" : "NOT met",
      median(watchLost) <= 10 ? "met" : "NOT met", median(busyLost) <= 10 ? "met" : "NOT met");
  return 0;
}

}  // namespace penumbra::ui
