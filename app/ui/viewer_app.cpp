#include "app/ui/viewer_app.h"

#include <unistd.h>
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <imgui.h>
#include <imgui_impl_opengl3.h>

#include "app/platform/platform.h"
#include "app/ui/image_display.h"
#include "app/ui/panels.h"
#include "app/ui/warp_inspector.h"
#include "core/analysis/convergence.h"
#include "core/analysis/error_metrics.h"
#include "core/analysis/order_statistics.h"
#include "core/image/image_io.h"
#include "core/image/tonemap.h"
#include "core/math/error.h"

namespace penumbra::ui {

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
double processCpuMs() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

// When the viewer draws (docs/viewer.md, "When the viewer redraws").
constexpr double kFrameIntervalMs = 1000.0 / 60.0;     // at most one frame per 60 Hz display refresh
constexpr double kSnapshotIntervalMs = 1000.0 / 30.0;  // new passes alone: at most 30 frames a second
// On software GL a frame's CPU time comes out of the render threads' cores (llvmpipe rasterises on
// them): frames that only show a new pass are spaced so that they take at most this share of all
// cores (~10 ms frames on 2 cores: ~8 a second). Input, restarts and display changes still draw at once.
constexpr double kPassFramesCpuShare = 0.04;
constexpr double kLongestPassIntervalMs = 250;  // but never fewer than 4 new passes shown a second
constexpr double kIdleWaitSeconds = 0.25;       // longest sleep (paces the scene file's check)
constexpr double kStatsRefreshMs = 500;         // while rendering, a frame at least this often
constexpr int kFramesAfterInput = 2;            // ImGui settles hover and click state a frame later

// Parts of a frame, timed separately by the bench's breakdown.
enum Stage { kUi, kTonemap, kImage, kPanels, kPresent, kStages };
constexpr const char* kStageNames[kStages] = {"ImGui build (NewFrame..Render)", "tone map + upload",
                                              "panel fill, background, image copy", "ImGui draw",
                                              "present (swap / finish)"};

class ViewerApp {
 public:
  ViewerApp(platform::Platform& p, ViewerController& c) : platform_(p), c_(c) {
    platform_.onDrop = [this](const std::vector<std::string>& files) {
      for (const std::string& f : files)
        if (f.size() > 4 && f.substr(f.size() - 4) == ".xml") {
          c_.openScene(f);
          break;
        }
    };
    // Wakes the UI thread's waitEvents when an engine publishes a snapshot (GLFW cannot wait on a
    // condition variable and window events at once).
    waker_ = std::thread([this] {
      const PublishSignal& signal = c_.publishSignal();
      for (uint64_t seen = signal.count(); !stopWaker_;) {
        uint64_t now = signal.wait(seen, 0.1);
        if (now != seen) platform_.wake();
        seen = now;
      }
    });
  }
  ~ViewerApp() {
    stopWaker_ = true;
    waker_.join();
  }

  // Takes in what changed outside the UI since the last call: new snapshots (marked for tone mapping),
  // compare mode switched or restarted, the scene file changed on disk. True when a frame is needed.
  bool update(bool requestSnapshot = true) {
    bool redraw = c_.checkFileChanged();
    // The whole image's standard error only for the false-colour view; the pixel inspector gets its
    // pixel's from the snapshot's probe (resolving 590 k pixels a pass for one cost the workers ~10 %).
    const bool wantError = c_.display.falseColour == FalseColour::RelativeError;
    c_.setProbePixel(st_.hoverValid ? st_.hoverX : -1, st_.hoverValid ? st_.hoverY : -1);
    c_.pollSnapshot(wantError, requestSnapshot);
    if (c_.compareEnabled() != compareShown_ || c_.compareRestartCount() != compareRestart_) {
      display_.clearCompare();  // never show the other strategy's old image on the right
      compareShown_ = c_.compareEnabled();
      compareRestart_ = c_.compareRestartCount();
      redraw = true;
    }
    if (c_.snapshotSerial() != seenSerial_) {
      seenSerial_ = c_.snapshotSerial();
      display_.snapshotChanged(0);
      redraw = true;
    }
    if (c_.compareSnapshotSerial() != seenCompareSerial_) {
      seenCompareSerial_ = c_.compareSnapshotSerial();
      display_.snapshotChanged(1);
      redraw = true;
    }
    return redraw;
  }

  // Draws and presents one frame: ImGui panels, the image area, swap (or finish offscreen).
  void frame() {
    const auto t0 = Clock::now();
    lastFrameStart_ = t0;
    stageStart();
    platform_.beginFrame();
    ImGui::NewFrame();
    if (!fontNearest_) {
      // The default font's glyphs are pixel-snapped and drawn 1:1, where nearest sampling equals the
      // backend's bilinear one; on llvmpipe it makes the panels ~10 % cheaper to draw.
      glBindTexture(GL_TEXTURE_2D, GLuint(intptr_t(ImGui::GetIO().Fonts->TexID)));
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      fontNearest_ = true;
    }
    int fbW = 0, fbH = 0;
    platform_.framebufferSize(fbW, fbH);
    layout_ = layoutImage(c_.display, c_.settings().camera.width, c_.settings().camera.height, kSidebarWidth,
                          std::max(fbW - kSidebarWidth, 1), fbH);
    handleInput();
    display_.dividerX = c_.compareEnabled() ? dividerScreenX() : 0.f;
    drawPanels(fbH);
    if (c_.compareEnabled()) drawCompareLabels();
    ImGui::Render();
    stageEnd(kUi);
    display_.prepare(c_.display, c_.snapshot(), c_.compareEnabled() ? &c_.compareSnapshot() : nullptr);
    stageEnd(kTonemap);

    // Every pixel is written once: the panel column's background (its ImGui window draws none:
    // blending a textured rectangle over 400 x fbH pixels costs llvmpipe ~3 ms, copying a solid one
    // ~0.3 ms), then the image area, then the panels.
    glViewport(0, 0, fbW, fbH);
    ImVec4 wb = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
    const float panelRgb[3] = {wb.x * wb.w + kBackgroundRgb[0] * (1 - wb.w),
                               wb.y * wb.w + kBackgroundRgb[1] * (1 - wb.w),
                               wb.z * wb.w + kBackgroundRgb[2] * (1 - wb.w)};
    display_.fillRect(fbH, 0, 0, std::min(kSidebarWidth, fbW), fbH, panelRgb);
    display_.draw(layout_, fbW, fbH, kSidebarWidth);
    stageEnd(kImage);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    stageEnd(kPanels);
    platform_.endFrame();
    stageEnd(kPresent);

    lastFrameMs_ = msSince(t0);
    st_.frameMs = lastFrameMs_;
    frameCostMs_ = framesDrawn_ == 0 ? lastFrameMs_ : 0.8 * frameCostMs_ + 0.2 * lastFrameMs_;
    ++framesDrawn_;
    shownRestart_ = c_.snapshot().mean.empty() ? 0 : c_.snapshotRestart();
    if (st_.requestSavePng) {
      st_.requestSavePng = false;
      try {
        st_.status = c_.saveImage(st_.savePath);
      } catch (const std::exception& e) {
        st_.status = e.what();
      }
    }
  }

  // Shortest spacing of frames that only show a new pass (see kPassFramesCpuShare).
  double passFrameIntervalMs() const {
    if (display_.tonemapper() != Tonemapper::Cpu) return kSnapshotIntervalMs;  // hardware GL
    const double cores = std::max(1u, std::thread::hardware_concurrency());
    return std::clamp(frameCostMs_ / (kPassFramesCpuShare * cores), kSnapshotIntervalMs,
                      kLongestPassIntervalMs);
  }

  // The interactive loop, until the window closes or `done()`. Event-driven: a frame is drawn when
  // input arrived (and kFramesAfterInput frames after it, and while an ImGui item is held), when a
  // new snapshot arrived (at most every passFrameIntervalMs(), except a restart's first image) or
  // compare mode changed, every kStatsRefreshMs while rendering, and never sooner than
  // kFrameIntervalMs after the previous one; in between the thread sleeps in waitEvents, so an idle
  // viewer costs nothing and a rendering one only the frames that show new passes. Snapshots are
  // requested only from about a pass and a half before one is due, so the workers resolve only
  // passes that will be shown. `continuous` draws every (paced) frame, as while a slider is dragged
  // (the bench measures both).
  template <class Done>
  void run(Done done, bool continuous = false) {
    int pending = 1;           // frames owed to input (or to `continuous`)
    bool snapshotDue = false;  // a new snapshot waits to be shown
    while (!platform_.shouldClose() && !done()) {
      platform_.pollEvents();
      if (platform_.eventCount() != seenEvents_) {
        seenEvents_ = platform_.eventCount();
        pending = std::max(pending, kFramesAfterInput);
      }
      const double since = msSince(lastFrameStart_);
      if (since < kFrameIntervalMs) {  // too soon for a frame: sleep until one is due (input wakes us)
        platform_.waitEvents((kFrameIntervalMs - since) * 1e-3);
        continue;
      }
      if (continuous) pending = std::max(pending, 1);
      const double passInterval = passFrameIntervalMs();
      const RenderProgress progress = c_.progress();
      const double passMs = progress.spp > 0 ? 1e3 * progress.seconds / progress.spp : 0.0;
      // Since the last frame; right after a restart the first pass is wanted at once.
      const double requestAtMs = progress.spp <= 1 ? 0.0 : passInterval - 1.5 * passMs;
      if (update(pending > 0 || since >= requestAtMs)) snapshotDue = true;
      // Slow passes (big images, heavy scenes): refresh the elapsed time and rates now and then.
      if (c_.rendering() && since >= kStatsRefreshMs) pending = std::max(pending, 1);
      // New passes of the same accumulation are shown at most every passInterval; the first images of
      // a new accumulation (the restart's preview, then its first pass) as soon as the 30 Hz cap allows.
      const bool firstOfRestart = c_.snapshotRestart() != shownRestart_ && !c_.snapshot().mean.empty();
      const bool firstPass = c_.snapshot().spp == 1 && since >= kSnapshotIntervalMs;
      const bool showSnapshot = snapshotDue && (firstOfRestart || firstPass || since >= passInterval);
      if (pending == 0 && !showSnapshot) {  // input, the waker on a new snapshot, or a due request
        double waitMs = snapshotDue ? passInterval - since : kIdleWaitSeconds * 1e3;
        if (since < requestAtMs) waitMs = std::min(waitMs, requestAtMs - since);
        platform_.waitEvents(std::max(waitMs, 1.0) * 1e-3);
        continue;
      }
      frame();
      snapshotDue = false;
      pending = std::max(pending - 1, 0);
      if (ImGui::IsAnyItemActive() || ImGui::IsAnyMouseDown()) pending = std::max(pending, 1);
    }
  }

  // Exactly `frames` frames, paced like the interactive loop (--frames: tests and screenshots).
  void runFrames(int frames, bool waitForTarget) {
    auto t0 = Clock::now();
    for (int f = 0; f < frames && !platform_.shouldClose(); ++f) {
      double early = kFrameIntervalMs - msSince(lastFrameStart_);
      if (early > 0) platform_.waitEvents(early * 1e-3);
      platform_.pollEvents();
      if (waitForTarget && f == frames - 1) {
        // Last frame: let the accumulation reach its limit first (bounded wait).
        while ((!c_.progress().finished || (c_.compareEnabled() && !c_.compareProgress().finished)) &&
               msSince(t0) < 120000)
          std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
      update();
      frame();
    }
  }

  const ImageLayout& layout() const { return layout_; }
  const ImageDisplay& display() const { return display_; }
  double lastFrameMs() const { return lastFrameMs_; }
  uint64_t framesDrawn() const { return framesDrawn_; }
  // Restart count of the image the last frame showed (0: none).
  uint64_t shownRestart() const { return shownRestart_; }
  // Bench breakdown: when set, each stage ends with glFinish and adds its wall and process CPU time.
  std::array<double, kStages>* stageWallMs = nullptr;
  std::array<double, kStages>* stageCpuMs = nullptr;
  void forceTonemap() { display_.snapshotChanged(0); }

 private:
  float dividerScreenX() const {
    return layout_.x + std::clamp(c_.display.compareDivider, 0.f, 1.f) * layout_.width * layout_.zoom;
  }

  // RMSE of a side against the Convergence panel's reference, recomputed when its snapshot changes.
  struct SideError {
    uint64_t version = ~0ull;
    uint32_t spp = ~0u;
    const Image* ref = nullptr;
    double rmse = -1;
  };
  double sideRmse(const FilmSnapshot& snap, SideError& cache) {
    const ConvergenceTracker& t = st_.convergence;
    if (!t.hasReference() || snap.mean.empty() || snap.spp == 0) return -1;
    const Reference& ref = t.reference();
    if (cache.version == snap.version && cache.spp == snap.spp && cache.ref == &ref.mean) return cache.rmse;
    cache.version = snap.version, cache.spp = snap.spp, cache.ref = &ref.mean;
    try {
      cache.rmse = computeErrors(snap.mean, ref.mean, ref.standardError).all.rmse;
    } catch (const std::exception&) {
      cache.rmse = -1;
    }
    return cache.rmse;
  }

  // "strategy  N spp  T s  RMSE E" above each side of the split image.
  void drawCompareLabels() {
    ImDrawList* dl = ImGui::GetForegroundDrawList();
    auto label = [&](const IntegratorDesc& d, const FilmSnapshot& snap, SideError& cache) {
      char buf[160];
      double e = sideRmse(snap, cache);
      int n = std::snprintf(buf, sizeof buf, "%s  %u spp  %.2f s", strategyLabel(d).c_str(), snap.spp,
                            snap.seconds);
      if (e >= 0) std::snprintf(buf + n, sizeof buf - n, "  RMSE %.4g", e);
      return std::string(buf);
    };
    IntegratorDesc right = c_.renderedCompareIntegrator();
    std::string a = label(c_.settings().integrator, c_.snapshot(), leftError_);
    std::string b = label(right, c_.compareSnapshot(), rightError_);
    // Left label at the image's top-left corner, right label at its top-right corner (one line lower
    // when they would overlap), both clipped to the visible image area.
    float x0 = std::max(layout_.x, float(kSidebarWidth)) + 6.f;
    float x1 = std::min(layout_.x + layout_.width * layout_.zoom, ImGui::GetIO().DisplaySize.x) - 6.f;
    float y = std::max(layout_.y, 0.f) + 6.f;
    ImVec2 sa = ImGui::CalcTextSize(a.c_str()), sb = ImGui::CalcTextSize(b.c_str());
    ImVec2 pa(x0, y), pb(std::max(x1 - sb.x, x0), y);
    if (pb.x < pa.x + sa.x + 12.f) pb.y += sa.y + 6.f;
    const ImU32 bg = IM_COL32(0, 0, 0, 170), fg = IM_COL32(235, 235, 235, 255);
    dl->AddRectFilled(ImVec2(pa.x - 3, pa.y - 2), ImVec2(pa.x + sa.x + 3, pa.y + sa.y + 2), bg);
    dl->AddText(pa, fg, a.c_str());
    dl->AddRectFilled(ImVec2(pb.x - 3, pb.y - 2), ImVec2(pb.x + sb.x + 3, pb.y + sb.y + 2), bg);
    dl->AddText(pb, fg, b.c_str());
  }

  void handleInput() {
    ImGuiIO& io = ImGui::GetIO();
    // Compare divider: a left drag that starts within a few pixels of it moves it (not the camera).
    if (!c_.compareEnabled()) draggingDivider_ = false;
    if (c_.compareEnabled() && layout_.width > 0 && !io.WantCaptureMouse) {
      ImVec2 p = io.MousePos;
      bool nearDivider = std::abs(p.x - dividerScreenX()) <= 6.f && p.y >= layout_.y &&
                         p.y < layout_.y + layout_.height * layout_.zoom;
      if (nearDivider || draggingDivider_) ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeEW);
      if (ImGui::IsMouseClicked(ImGuiMouseButton_Left) && nearDivider) draggingDivider_ = true;
    }
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) draggingDivider_ = false;
    if (draggingDivider_) {
      float w = std::max(layout_.width * layout_.zoom, 1.f);
      c_.display.compareDivider = std::clamp((io.MousePos.x - layout_.x) / w, 0.f, 1.f);
    }
    // Pixel inspector and camera: only when the cursor is over the image area, not over a panel.
    st_.hoverValid = false;
    ImVec2 m = io.MousePos;
    bool overArea = !io.WantCaptureMouse && m.x >= kSidebarWidth && m.x >= 0 && m.y >= 0;
    if (overArea && layout_.width > 0) {
      int px = int(std::floor((m.x - layout_.x) / layout_.zoom));
      int py = int(std::floor((m.y - layout_.y) / layout_.zoom));
      const Image& img = c_.snapshot().mean;
      if (px >= 0 && py >= 0 && px < img.width && py < img.height) {
        st_.hoverValid = true;
        st_.hoverX = px;
        st_.hoverY = py;
      }
    }
    if (!io.WantCaptureMouse) {
      ImVec2 d = io.MouseDelta;
      if (ImGui::IsMouseDragging(ImGuiMouseButton_Left) && !draggingDivider_ && (d.x != 0 || d.y != 0))
        c_.orbit(d.x, d.y);
      if ((ImGui::IsMouseDragging(ImGuiMouseButton_Right) ||
           ImGui::IsMouseDragging(ImGuiMouseButton_Middle)) &&
          (d.x != 0 || d.y != 0))
        c_.pan(d.x / std::max(layout_.zoom, 1e-3f), d.y / std::max(layout_.zoom, 1e-3f));
      if (io.MouseWheel != 0 && overArea) {
        if (io.KeyCtrl) {
          c_.display.zoom = std::clamp(c_.display.zoom * std::pow(1.25f, io.MouseWheel), 1.f / 16, 16.f);
          if (c_.display.fit) c_.display.zoom = layout_.zoom * std::pow(1.25f, io.MouseWheel);
          c_.display.fit = false;
        } else {
          c_.dolly(io.MouseWheel);
        }
      }
    }
    if (!io.WantTextInput) {
      for (ImWchar ch : io.InputQueueCharacters) {
        switch (ch) {
          case ' ':
            c_.setPaused(!c_.paused());
            break;
          case 'r':
          case 'R':
            c_.restart();
            break;
          case 's':
          case 'S':
            st_.requestSavePng = true;
            break;
          case 'f':
          case 'F':
            c_.display.fit = true;
            c_.display.panX = c_.display.panY = 0;
            break;
          case '+':
          case '=':
            c_.display.exposure += 0.5f;
            break;
          case '-':
          case '_':
            c_.display.exposure -= 0.5f;
            break;
          case 'h':
          case 'H':
          case '?':
            st_.showHelp = !st_.showHelp;
            break;
          default:
            break;
        }
      }
    }
  }

  void drawPanels(int fbH) {
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(float(kSidebarWidth), float(fbH)));
    ImGui::Begin("Penumbra", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBackground);  // frame() clears it
    ImGui::PushItemWidth(-130);
    drawScenePanel(c_, st_);
    drawIntegratorPanel(c_, st_);
    drawSamplerPanel(c_, st_);
    drawCameraPanel(c_, st_);
    drawDisplayPanel(c_, st_);
    drawStatsPanel(c_, st_);
    drawConvergencePanel(c_, st_);
    ImGui::PopItemWidth();
    ImGui::Separator();
    if (ImGui::Button("Help (H)")) st_.showHelp = !st_.showHelp;
    ImGui::SameLine();
    if (ImGui::Button("Warp inspector")) showWarpInspector_ = !showWarpInspector_;
    ImGui::End();
    drawHelpPanel(c_, st_);
    if (showWarpInspector_) {
      if (!warpInspector_) warpInspector_ = std::make_unique<WarpInspector>();
      warpInspector_->draw(&showWarpInspector_, false);
    }
  }

  void stageStart() {
    if (!stageWallMs) return;
    stageT_ = Clock::now();
    stageC_ = processCpuMs();
  }
  void stageEnd(Stage s) {
    if (!stageWallMs) return;
    glFinish();
    double c = processCpuMs();
    (*stageWallMs)[s] += msSince(stageT_);
    (*stageCpuMs)[s] += c - stageC_;
    stageT_ = Clock::now();
    stageC_ = c;
  }

  platform::Platform& platform_;
  ViewerController& c_;
  ImageDisplay display_;
  PanelState st_;
  ImageLayout layout_;
  std::unique_ptr<WarpInspector> warpInspector_;  // created when first opened
  bool showWarpInspector_ = false;
  bool draggingDivider_ = false;
  bool compareShown_ = false;
  uint64_t compareRestart_ = 0;
  SideError leftError_, rightError_;
  uint64_t seenSerial_ = ~0ull, seenCompareSerial_ = ~0ull, seenEvents_ = ~0ull;
  Clock::time_point lastFrameStart_{};
  double lastFrameMs_ = 0;
  double frameCostMs_ = 0;  // running average of lastFrameMs_ (paces pass-only frames)
  uint64_t framesDrawn_ = 0;
  uint64_t shownRestart_ = 0;
  Clock::time_point stageT_{};
  double stageC_ = 0;
  bool fontNearest_ = false;
  std::atomic<bool> stopWaker_{false};
  std::thread waker_;
};

// CPU time of this process's threads, split by role (Linux /proc; ms). The UI thread is the main
// thread; the GL rasteriser's threads are Mesa's "llvmpipe-N"; everything else (the render workers,
// which come and go with every restart) is the process total minus those two.
struct CpuSplit {
  double ui = 0, gl = 0, total = 0;
};
CpuSplit cpuSplit() {
  CpuSplit c;
  c.total = processCpuMs();
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

Phase runPhase(ViewerApp& app, ViewerController& c, double seconds, Mode mode) {
  Phase r;
  c.restart();
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
int runBench(platform::Platform& p, ViewerController& c, ViewerApp& app) {
  const RenderSettings& s = c.settings();
  const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
  std::printf("bench: %s, %dx%d, %s, %d worker threads (nice %d), %d cores, %s, tone mapping on the %s\n",
              p.name(), s.camera.width, s.camera.height, strategyLabel(s.integrator).c_str(),
              c.engine().threadCount(), kViewerWorkerNice, cores, p.glRenderer().c_str(),
              app.display().tonemapper() == Tonemapper::Cpu ? "CPU (software GL)" : "GPU (display.frag)");
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
    app.run([&] { return msSince(w0) >= 150 + 37 * i; });  // a different phase of the pass each time
    RenderSettings next = c.settings();
    next.seed += 1;
    auto r0 = Clock::now();
    c.setSettings(next);
    handled.push_back(msSince(r0));
    const uint64_t restart = c.restartCount();
    double shown = -1;
    app.run([&] {
      if (shown < 0 && app.shownRestart() == restart) {
        shown = msSince(r0);
        if (c.snapshot().spp == 0) previewEngine.push_back(c.snapshot().seconds * 1e3);
      }
      return (app.shownRestart() == restart && c.snapshot().spp >= 1) || msSince(r0) > 10000;
    });
    latency.push_back(shown < 0 ? msSince(r0) : shown);
    fullPass.push_back(msSince(r0));
  }

  // Where a frame's time goes: engine paused (so the CPU time is the UI's and GL's alone), every
  // frame tone mapping the image as a frame with a new snapshot does, glFinish after each stage.
  c.setPaused(true);
  std::array<double, kStages> wall{}, cpu{};
  app.stageWallMs = &wall;
  app.stageCpuMs = &cpu;
  const int breakdownFrames = 100;
  for (int i = 0; i < breakdownFrames; ++i) {
    app.forceTonemap();
    app.frame();
  }
  app.stageWallMs = app.stageCpuMs = nullptr;
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
  for (int i = 0; i < kStages; ++i)
    std::printf("bench:   %-32s %6.2f ms wall %6.2f ms CPU\n", kStageNames[i], wall[i] / breakdownFrames,
                cpu[i] / breakdownFrames);
  double frameMs = std::max(median(watchFrames), median(busyFrames));
  std::printf(
      "bench: targets: >= 60 fps (frame time <= 16.7 ms): %s; <= 50 ms restart latency: %s; <= 10 %% lost: "
      "%s while watching, %s while dragging the exposure\n",
      frameMs <= 1000.0 / 60 ? "met" : "NOT met", median(latency) <= 50 ? "met" : "NOT met",
      median(watchLost) <= 10 ? "met" : "NOT met", median(busyLost) <= 10 ? "met" : "NOT met");
  return 0;
}

void writeScreenshot(platform::Platform& p, const std::string& path) {
  int w = 0, h = 0;
  std::vector<std::uint8_t> rgb = p.readPixels(w, h);
  Image img(w, h);
  for (size_t i = 0; i < rgb.size(); ++i) img.rgb[i] = srgbToLinear(rgb[i] / 255.f);
  // Decoding to linear and re-encoding through toSrgb8 returns the same bytes.
  writeImage(path, img);
}

}  // namespace

int runViewer(LoadedScene scene, ViewerController::Overrides overrides, const ViewerOptions& o) {
  ViewerController controller(std::move(scene), std::move(overrides), o.threads);
  const CameraDesc& cam = controller.settings().camera;
  platform::WindowOptions wo;
  wo.width = o.windowWidth > 0 ? o.windowWidth : kSidebarWidth + std::clamp(cam.width, 512, 1280);
  wo.height = o.windowHeight > 0 ? o.windowHeight : std::clamp(cam.height, 720, 960);
  wo.title = "Penumbra — " +
             (controller.scene().path.empty() ? std::string("built-in scene") : controller.scene().path);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsDark();
  int rc = 0;
  {
    std::unique_ptr<platform::Platform> p = platform::createPlatform(wo);
    ViewerApp app(*p, controller);
    if (!o.compare.empty()) {
      std::vector<IntegratorDesc> d = parseStrategies(controller.settings().integrator, o.compare);
      if (d.size() != 1) throw Error("--compare " + o.compare + ": expected one strategy");
      controller.setCompareIntegrator(d[0]);
      controller.setCompare(true);  // starts both sides
    } else {
      controller.start();
    }
    if (o.bench) {
      rc = runBench(*p, controller, app);
    } else {
      if (o.frames > 0)
        app.runFrames(o.frames, o.waitForTarget);
      else
        app.run([] { return false; });
      if (o.printLayout) {
        const ImageLayout& l = app.layout();
        std::printf("image-rect %g %g %d %d %g\n", l.x, l.y, l.width, l.height, l.zoom);
        RenderProgress pr = controller.progress();
        std::printf("spp %u restarts %llu\n", pr.spp, (unsigned long long)controller.restartCount());
        std::printf("tone mapping: %s\n", tonemapperName(app.display().tonemapper()));
      }
      if (!o.screenshot.empty()) {
        writeScreenshot(*p, o.screenshot);
        std::printf("wrote %s (%s, %u spp)\n", o.screenshot.c_str(), p->name(), controller.progress().spp);
      }
    }
    controller.engine().cancel();
  }
  ImGui::DestroyContext();
  return rc;
}

}  // namespace penumbra::ui
