#include "app/ui/viewer_app.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <imgui.h>
#include <imgui_impl_opengl3.h>
#include <imgui_internal.h>  // the panel window's item extent (--print-layout)

#include "app/platform/platform.h"
#include "app/ui/frame_driver.h"
#include "app/ui/image_display.h"
#include "app/ui/key_bindings.h"
#include "app/ui/number_input.h"
#include "app/ui/panel_layout.h"
#include "app/ui/panel_text.h"
#include "app/ui/panels.h"
#include "app/ui/readouts.h"
#include "app/ui/run_queue_wait.h"
#include "app/ui/ui_clock.h"
#include "app/ui/viewer_bench.h"
#include "app/ui/warp_inspector.h"
#include "core/analysis/convergence.h"
#include "core/analysis/error_metrics.h"
#include "core/image/image_io.h"
#include "core/image/tonemap.h"
#include "core/math/error.h"

namespace penumbra::ui {

namespace {

// When the viewer draws (docs/viewer.md, "When the viewer redraws").
constexpr double kFrameIntervalMs = 1000.0 / 60.0;     // at most one frame per 60 Hz display refresh
constexpr double kSnapshotIntervalMs = 1000.0 / 30.0;  // new passes alone: at most 30 frames a second
// On software GL a frame's CPU time comes out of the render threads' cores (llvmpipe rasterises on
// them): frames that only show a new pass are spaced so that they, with the workers' resolving of the
// passes they show, take at most this share of all cores (~10 ms frames on 2 cores: ~8 a second).
// Input, restarts and display changes still draw at once.
constexpr double kPassFramesCpuShare = 0.04;
constexpr double kLongestPassIntervalMs = 250;  // but never fewer than 4 new passes shown a second
constexpr double kIdleWaitSeconds = 0.25;       // longest sleep (paces the scene file's check)
constexpr double kStatsRefreshMs = 500;         // while rendering, a frame at least this often
constexpr int kFramesAfterInput = 2;            // ImGui settles hover and click state a frame later

class ViewerApp : public BenchViewer, public DrivenViewer {
 public:
  ViewerApp(platform::Platform& p, ViewerController& c) : platform_(p), c_(c) {
    platform_.onDrop = [this](const std::vector<std::string>& files) {
      for (const std::string& f : files)
        if (f.size() > 4 && f.substr(f.size() - 4) == ".xml") {
          c_.openSceneAsync(f);
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
  virtual ~ViewerApp() {
    stopWaker_ = true;
    waker_.join();
  }

  // Takes in what changed outside the UI since the last call: new snapshots (marked for tone mapping),
  // compare mode switched or restarted, the scene file changed on disk. True when a frame is needed.
  bool update(bool requestSnapshot = true) {
    bool redraw = c_.checkFileChanged();
    // The whole image's standard error only for the false-colour view; the pixel inspector gets its
    // pixel's from the snapshot's probe (resolving 590 k pixels a pass for one cost the workers ~10 %).
    const bool wantError = c_.shownDisplay().falseColour == FalseColour::RelativeError;
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
  void frame() override {
    const auto t0 = Clock::now();
    lastFrameStart_ = t0;
    if (stageTimer_) stageTimer_->begin();
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
    if (c_.windowTitle() != title_) platform_.setTitle(title_ = c_.windowTitle());
    // The column follows the window's width until the user drags its edge.
    if (!sidebarDragged_ || fbW != sidebarWindowWidth_) {
      if (!sidebarDragged_) sidebarWidth_ = defaultSidebarWidth(fbW);
      sidebarWindowWidth_ = fbW;
      panelHeight_ = -1;  // SetNextWindowSize again
    }
    sidebarWidth_ = std::clamp(sidebarWidth_, minSidebarWidth(fbW), maxSidebarWidth(fbW));
    const int sidebar = sidebarWidth_;  // this frame's panel column (resizable: drag its edge)
    layout_ = layoutImage(c_.display, c_.settings().camera.width, c_.settings().camera.height, sidebar,
                          std::max(fbW - sidebar, 1), fbH);
    st_.layoutZoom = layout_.zoom;
    handleInput();
    display_.dividerX = c_.compareEnabled() ? dividerScreenX() : 0.f;
    drawPanels(fbW, fbH);
    if (c_.compareEnabled()) drawCompareLabels();
    if (c_.loading())
      drawLoadingOverlay(fbW, fbH);
    else
      drawPassOverlay(fbW, fbH);
    ImGui::Render();
    if (stageTimer_) stageTimer_->end(kUi);
    display_.prepare(c_.shownDisplay(), c_.snapshot(), c_.compareEnabled() ? &c_.compareSnapshot() : nullptr);
    if (stageTimer_) stageTimer_->end(kTonemap);

    // Every pixel is written once: the panel column's background (its ImGui window draws none:
    // blending a textured rectangle over 400 x fbH pixels costs llvmpipe ~3 ms, copying a solid one
    // ~0.3 ms), then the image area, then the panels.
    glViewport(0, 0, fbW, fbH);
    ImVec4 wb = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
    const float panelRgb[3] = {wb.x * wb.w + kBackgroundRgb[0] * (1 - wb.w),
                               wb.y * wb.w + kBackgroundRgb[1] * (1 - wb.w),
                               wb.z * wb.w + kBackgroundRgb[2] * (1 - wb.w)};
    display_.fillRect(fbH, 0, 0, std::min(sidebar, fbW), fbH, panelRgb);
    display_.draw(layout_, fbW, fbH, sidebar);
    if (stageTimer_) stageTimer_->end(kImage);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (stageTimer_) stageTimer_->end(kPanels);
    platform_.endFrame();
    if (stageTimer_) stageTimer_->end(kPresent);

    lastFrameMs_ = msSince(t0);
    st_.frameMs = lastFrameMs_;
    frameCostMs_ = framesDrawn_ == 0 ? lastFrameMs_ : 0.8 * frameCostMs_ + 0.2 * lastFrameMs_;
    // The workers' resolving since the last frame that saw some: the cost of the pass this one shows.
    const double resolved = c_.progress().resolveSeconds;
    if (resolved < resolvedSeconds_) resolvedSeconds_ = resolved;  // another engine (a new scene)
    if (resolved > resolvedSeconds_) {
      const double ms = 1e3 * (resolved - resolvedSeconds_);
      resolveCostMs_ = resolveCostMs_ == 0 ? ms : 0.8 * resolveCostMs_ + 0.2 * ms;
      resolvedSeconds_ = resolved;
    }
    ++framesDrawn_;
    shownRestart_ = c_.snapshot().mean.empty() ? 0 : c_.snapshotRestart();
    if (st_.requestSavePng) {
      st_.requestSavePng = false;
      try {
        if (st_.imageSaveGuard.allows(st_.savePath))
          c_.setOutputStatus(c_.saveImage(st_.savePath));
        else
          c_.setOutputStatus(OverwriteGuard::refusal(st_.savePath, "Save (or S)"));
      } catch (const std::exception& e) {
        c_.setOutputStatus(e.what());
      }
    }
  }

  // Shortest spacing of frames that only show a new pass (see kPassFramesCpuShare).
  double passFrameIntervalMs() const {
    if (display_.tonemapper() != Tonemapper::Cpu) return kSnapshotIntervalMs;  // hardware GL
    const double cores = std::max(1u, std::thread::hardware_concurrency());
    return std::clamp((frameCostMs_ + resolveCostMs_) / (kPassFramesCpuShare * cores), kSnapshotIntervalMs,
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
  void run(const std::function<bool()>& done, bool continuous = false) override {
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
      const double requestAtMs = progress.spp <= 1 ? 0.0 : passInterval - 2.5 * passMs;
      if (update(pending > 0 || (since >= requestAtMs && !snapshotDue))) snapshotDue = true;
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

  // Frames under a driver's input and checks (--monkey, --audit-ids), back to back: no pacing, so
  // that thousands of frames take minutes. Returns the driver's exit code.
  int runDriven(FrameDriver& driver) {
    FrameStageTimer stages;  // each frame's breakdown, for the report of a slow one
    stageTimer_ = &stages;
    RunQueueWait cpuWait;
    cpuWait.sinceLast();
    for (int f = 0; driver.beforeFrame(f, *this); ++f) {
      const auto t0 = Clock::now();
      const double loading0 = c_.blockingLoadSeconds();
      stages = FrameStageTimer();
      try {
        update();
        updateMs_ = msSince(t0);
        frame();
      } catch (const std::exception& e) {
        driver.frameThrew(f, e.what());
        break;
      }
      const double loading = c_.blockingLoadSeconds() - loading0, waiting = cpuWait.sinceLast();
      const double wall = msSince(t0) * 1e-3;
      char buf[300];
      std::snprintf(
          buf, sizeof buf,
          "wall %.0f ms: snapshot poll %.0f, panels %.0f, tone mapping %.0f, image %.0f, ImGui drawing "
          "%.0f, present %.0f; of which loading scenes %.0f, waiting for a CPU %.0f",
          wall * 1e3, updateMs_, stages.wallMs[kUi], stages.wallMs[kTonemap], stages.wallMs[kImage],
          stages.wallMs[kPanels], stages.wallMs[kPresent], loading * 1e3, waiting * 1e3);
      frameBreakdown_ = buf;
      if (!driver.afterFrame(f, *this, wall - loading - waiting)) break;
    }
    stageTimer_ = nullptr;
    return driver.exitCode();
  }

  // DrivenViewer.
  ViewerController& controller() override { return c_; }
  void setWarpInspectorOpen(bool open) override { showWarpInspector_ = open; }
  bool warpInspectorOpen() const override { return showWarpInspector_; }
  void setHelpOpen(bool open) override { st_.showHelp = open; }
  void windowSize(int& width, int& height) const override { platform_.framebufferSize(width, height); }
  std::string lastFrameBreakdown() const override { return frameBreakdown_; }

  const ImageLayout& layout() const { return layout_; }
  int sidebarWidth() const { return sidebarWidth_; }
  const std::vector<std::pair<std::string, float>>& sectionTops() const { return sectionTops_; }
  float panelOverflow() const { return panelOverflow_; }
  void openWarpInspector() { showWarpInspector_ = true; }
  const std::string& referenceError() const { return st_.convergence.error(); }
  // As typed into the Convergence panel's reference field and loaded (a failure shows there).
  void loadReference(const std::string& path) {
    std::snprintf(st_.referencePath, sizeof st_.referencePath, "%s", path.c_str());
    st_.convergence.update(c_);  // keys the tracker to this scene first, which would drop the reference
    st_.convergence.loadReference(c_, path);
  }
  const ImageDisplay& display() const { return display_; }

  // BenchViewer.
  double lastFrameMs() const override { return lastFrameMs_; }
  uint64_t framesDrawn() const override { return framesDrawn_; }
  uint64_t shownRestart() const override { return shownRestart_; }
  Tonemapper tonemapper() const override { return display_.tonemapper(); }
  void forceTonemap() override { display_.snapshotChanged(0); }
  void timeStages(FrameStageTimer* timer) override { stageTimer_ = timer; }

 private:
  // The image area's rectangle on screen (the image clipped to the area right of the panels).
  ImVec4 imageRect(int fbW, int fbH) const {
    const float x0 = std::max(layout_.x, float(sidebarWidth_)), y0 = std::max(layout_.y, 0.f);
    const float x1 = std::min(layout_.x + layout_.width * layout_.zoom, float(fbW));
    const float y1 = std::min(layout_.y + layout_.height * layout_.zoom, float(fbH));
    return ImVec4(x0, y0, x1, y1);
  }

  // A slow accumulation: an image left over from before the last change is dimmed under what is
  // coming ("rendering pass 1: 120 of 480 rows ..."); a slow first pass over its preview is labelled.
  void drawPassOverlay(int fbW, int fbH) {
    const RenderProgress p = c_.progress();
    const bool noImage = c_.snapshot().mean.empty();
    const bool stale =
        !noImage && imageIsStale(c_.snapshotRestart(), c_.restartCount(), c_.secondsSinceRestart());
    const bool slowFirstPass = p.spp == 0 && !p.finished && passElapsed(p) >= kSlowPassSeconds;
    if (!stale && !slowFirstPass) return;
    const ImVec4 r = imageRect(fbW, fbH);
    if (r.z <= r.x || r.w <= r.y) return;
    ImDrawList* dl = ImGui::GetBackgroundDrawList();
    std::string text;
    if (stale) {
      dl->AddRectFilled(ImVec2(r.x, r.y), ImVec2(r.z, r.w), IM_COL32(20, 20, 20, 170));
      text = c_.paused() ? "paused: the image is from before your change (Space resumes)"
                         : "rendering the new image; this one is from before your change";
    } else {
      text = noImage ? "rendering the first image" : "first pass";
    }
    const std::string pass = passProgressText(p);
    if (!c_.paused() && !pass.empty()) text += "\n" + pass;
    const float wrap = std::max(r.z - r.x - 24.f, 60.f);
    const ImVec2 size = ImGui::CalcTextSize(text.c_str(), nullptr, false, wrap);
    // Centred over a dimmed image or where the image will be; at the bottom of a preview, which is
    // the new estimate.
    const ImVec2 at(
        r.x + std::max(12.f, (r.z - r.x - size.x) * 0.5f),
        stale || noImage ? r.y + std::max(12.f, (r.w - r.y - size.y) * 0.5f) : r.w - size.y - 12.f);
    dl->AddRectFilled(ImVec2(at.x - 6, at.y - 4), ImVec2(at.x + size.x + 6, at.y + size.y + 4),
                      IM_COL32(0, 0, 0, 190));
    dl->AddText(nullptr, 0.f, at, IM_COL32(240, 220, 150, 255), text.c_str(), nullptr, wrap);
  }

  // While a scene loads: the old image dimmed, and what is loading.
  void drawLoadingOverlay(int fbW, int fbH) {
    ImDrawList* dl = ImGui::GetBackgroundDrawList();
    const float x0 = float(sidebarWidth_);
    dl->AddRectFilled(ImVec2(x0, 0), ImVec2(float(fbW), float(fbH)), IM_COL32(20, 20, 20, 200));
    char buf[1200];
    std::snprintf(buf, sizeof buf, "loading %s ...\n(parsing, meshes, BVH build: the old scene is dimmed)",
                  c_.loadingPath().c_str());
    ImVec2 size = ImGui::CalcTextSize(buf, nullptr, false, float(fbW) - x0 - 24.f);
    ImVec2 p(x0 + std::max(12.f, (float(fbW) - x0 - size.x) * 0.5f), std::max(12.f, (fbH - size.y) * 0.5f));
    dl->AddText(nullptr, 0.f, p, IM_COL32(240, 220, 150, 255), buf, nullptr, float(fbW) - x0 - 24.f);
  }

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
    float x0 = std::max(layout_.x, float(sidebarWidth_)) + 6.f;
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
    const unsigned held = io.KeyCtrl ? kCtrl : kNoModifier;
    if (draggingDivider_) perform(Trigger::LeftDragOnDivider, held);
    // Pixel inspector and camera: only when the cursor is over the image area, not over a panel.
    st_.hoverValid = false;
    ImVec2 m = io.MousePos;
    bool overArea = !io.WantCaptureMouse && m.x >= sidebarWidth_ && m.x >= 0 && m.y >= 0;
    if (overArea && layout_.width > 0) {
      int px, py;
      const Image& img = c_.snapshot().mean;
      if (imagePixelAt(layout_, m.x, m.y, px, py) && px < img.width && py < img.height) {
        st_.hoverValid = true;
        st_.hoverX = px;
        st_.hoverY = py;
      }
    }
    if (!io.WantCaptureMouse) {
      const bool moved = io.MouseDelta.x != 0 || io.MouseDelta.y != 0;
      if (ImGui::IsMouseDragging(ImGuiMouseButton_Left) && !draggingDivider_ && moved)
        perform(Trigger::LeftDrag, held);
      if ((ImGui::IsMouseDragging(ImGuiMouseButton_Right) ||
           ImGui::IsMouseDragging(ImGuiMouseButton_Middle)) &&
          moved)
        perform(Trigger::RightOrMiddleDrag, held);
      if (io.MouseWheel != 0 && overArea) perform(Trigger::Wheel, held);
    }
    if (!io.WantTextInput)
      for (ImWchar ch : io.InputQueueCharacters) perform(Trigger::Key, held, ch);
  }

  // Does what the key-binding table binds to this input (nothing when it binds nothing).
  void perform(Trigger trigger, unsigned held, char32_t ch = 0) {
    const KeyBinding* binding = findBinding(trigger, held, ch);
    if (!binding) return;
    const ImGuiIO& io = ImGui::GetIO();
    const ImVec2 d = io.MouseDelta;
    DisplaySettings& display = c_.display;
    switch (binding->action) {
      case ViewerAction::TogglePause:
        c_.setPaused(!c_.paused());
        break;
      case ViewerAction::Restart:
        c_.restart();
        break;
      case ViewerAction::SavePng:
        st_.requestSavePng = true;
        break;
      case ViewerAction::FitImage:
        display.fit = true;
        display.panX = display.panY = 0;
        break;
      case ViewerAction::ExposureUp:
        display.exposure += 0.5f;
        break;
      case ViewerAction::ExposureDown:
        display.exposure -= 0.5f;
        break;
      case ViewerAction::ToggleHelp:
        st_.showHelp = !st_.showHelp;
        break;
      case ViewerAction::Orbit:
        c_.orbit(d.x, d.y);
        break;
      case ViewerAction::MoveDivider:
        display.compareDivider =
            std::clamp((io.MousePos.x - layout_.x) / std::max(layout_.width * layout_.zoom, 1.f), 0.f, 1.f);
        break;
      case ViewerAction::Pan:
        c_.pan(d.x / std::max(layout_.zoom, 1e-3f), d.y / std::max(layout_.zoom, 1e-3f));
        break;
      case ViewerAction::Dolly:
        c_.dolly(io.MouseWheel);
        break;
      case ViewerAction::ZoomDisplay:
        display.zoom = zoomAfterWheel(display, layout_.zoom, io.MouseWheel);
        display.fit = false;
        break;
    }
  }

  void drawPanels(int fbW, int fbH) {
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    // The column's height follows the window; its width is the user's (drag the right edge).
    if (fbH != panelHeight_) ImGui::SetNextWindowSize(ImVec2(float(sidebarWidth_), float(fbH)));
    panelHeight_ = fbH;
    ImGui::SetNextWindowSizeConstraints(ImVec2(float(minSidebarWidth(fbW)), float(fbH)),
                                        ImVec2(float(maxSidebarWidth(fbW)), float(fbH)));
    ImGui::Begin("Penumbra", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings |
                     ImGuiWindowFlags_NoBackground);  // frame() clears it
    const int width = int(ImGui::GetWindowWidth());
    if (width != sidebarWidth_ && ImGui::IsMouseDown(ImGuiMouseButton_Left)) sidebarDragged_ = true;
    sidebarWidth_ = width;
    // State about the previous scene ends with it: the fields' notes.
    if (c_.sceneSerial() != seenScene_) {
      seenScene_ = c_.sceneSerial();
      forgetNumberNotes();
    }
    // Labels get a column; widgets take the rest, so wider panels give the values room. Every text
    // wraps at the column's edge instead of being cut off.
    ImGui::PushItemWidth(-labelColumnWidth(sidebarWidth_));
    ImGui::PushTextWrapPos(0.f);
    const std::pair<const char*, void (*)(ViewerController&, PanelState&)> sections[] = {
        {"Scene", drawScenePanel},   {"Integrator", drawIntegratorPanel},  {"Sampler", drawSamplerPanel},
        {"Camera", drawCameraPanel}, {"Materials", drawMaterialsPanel},    {"Display", drawDisplayPanel},
        {"Stats", drawStatsPanel},   {"Convergence", drawConvergencePanel}};
    sectionTops_.clear();
    for (const auto& [name, draw] : sections) {
      if (draw == drawMaterialsPanel && c_.glossyBsdfEntries().empty()) continue;  // diffuse scenes: none
      sectionTops_.emplace_back(name, ImGui::GetCursorScreenPos().y);
      draw(c_, st_);
    }
    ImGui::PopTextWrapPos();
    ImGui::PopItemWidth();
    ImGui::Separator();
    if (ImGui::Button("Help (H)")) st_.showHelp = !st_.showHelp;
    sameLineIfFits(buttonWidth("Warp inspector"));
    if (ImGui::Button("Warp inspector")) showWarpInspector_ = !showWarpInspector_;
    // How far the widest item reaches past the column's content region (text cut off at its edge).
    panelOverflow_ = ImGui::GetCurrentWindow()->DC.CursorMaxPos.x -
                     (ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x);
    ImGui::End();
    drawHelpPanel(c_, st_);
    if (showWarpInspector_) {
      if (!warpInspector_) warpInspector_ = std::make_unique<WarpInspector>();
      warpInspector_->draw(&showWarpInspector_, false);
    }
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
  double frameCostMs_ = 0;      // running average of lastFrameMs_ (paces pass-only frames)
  double resolveCostMs_ = 0;    // running average of the workers' resolving per shown pass (paces them too)
  double resolvedSeconds_ = 0;  // RenderProgress::resolveSeconds at the last frame that saw it grow
  uint64_t framesDrawn_ = 0;
  uint64_t shownRestart_ = 0;
  FrameStageTimer* stageTimer_ = nullptr;  // the bench's (and runDriven's) frame breakdown
  double updateMs_ = 0;
  std::string frameBreakdown_;
  bool fontNearest_ = false;
  int sidebarWidth_ = 0;         // the panel column (0: not yet chosen)
  int sidebarWindowWidth_ = -1;  // the window width sidebarWidth_ was chosen for
  bool sidebarDragged_ = false;  // the user chose the width: keep it
  uint64_t seenScene_ = 0;
  std::vector<std::pair<std::string, float>> sectionTops_;  // --print-layout: each section's top
  float panelOverflow_ = 0;  // --print-layout: > 0 when an item of the panels passes the column's edge
  int panelHeight_ = -1;
  std::string title_;
  std::atomic<bool> stopWaker_{false};
  std::thread waker_;
};

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
  if (o.loadSeconds > 0) controller.noteLoadSeconds(o.loadSeconds);
  if (o.onSnapshot) controller.onSnapshotPolled = [&o](const ViewerController& c) { o.onSnapshot(c, false); };
  const CameraDesc& cam = controller.settings().camera;
  platform::WindowOptions wo;
  wo.width = o.windowWidth > 0 ? o.windowWidth : kSidebarWidth + std::clamp(cam.width, 512, 1280);
  wo.height = o.windowHeight > 0 ? o.windowHeight : std::clamp(cam.height, 720, 960);
  wo.title = "Penumbra — " +
             (controller.scene().path.empty() ? std::string("built-in scene") : controller.scene().path);

  if (o.lightShareView && (!o.compare.empty() || !controller.lightShareOffered()))
    throw Error(
        "--view mis-light-share: needs a mis strategy that applies to the scene (e.g. --set "
        "integrator.measure=mis) and no --compare; the scene renders " +
        strategyLabel(controller.settings().integrator));

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsDark();
  int rc = 0;
  {
    std::unique_ptr<platform::Platform> p = platform::createPlatform(wo);
    ViewerApp app(*p, controller);
    if (o.openWarpInspector) app.openWarpInspector();
    if (!o.reference.empty()) app.loadReference(o.reference);
    if (!o.compare.empty()) {
      controller.setCompareIntegrator(controller.parseCompareStrategy(o.compare));
      controller.setCompare(true);  // starts both sides
    } else if (o.lightShareView) {
      controller.setLightShareView(true);  // starts the accumulation
    } else {
      controller.start();
    }
    if (o.bench) {
      rc = runViewerBench(*p, controller, app);
    } else if (o.driver) {
      rc = app.runDriven(*o.driver);
    } else {
      if (o.frames > 0)
        app.runFrames(o.frames, o.waitForTarget);
      else
        app.run([] { return false; });
      if (o.printLayout) {
        const ImageLayout& l = app.layout();
        std::printf("image-rect %g %g %d %d %g\n", l.x, l.y, l.width, l.height, l.zoom);
        std::printf("sidebar %d\n", app.sidebarWidth());
        std::printf("panel-overflow %g\n", app.panelOverflow());
        for (const auto& [name, y] : app.sectionTops()) std::printf("section %s %g\n", name.c_str(), y);
        RenderProgress pr = controller.progress();
        std::printf("spp %u restarts %llu\n", pr.spp, (unsigned long long)controller.restartCount());
        std::printf("tone mapping: %s\n", tonemapperName(app.display().tonemapper()));
        if (!app.referenceError().empty()) std::printf("reference-error %s\n", app.referenceError().c_str());
      }
      if (!o.screenshot.empty()) {
        writeScreenshot(*p, o.screenshot);
        std::printf("wrote %s (%s, %u spp)\n", o.screenshot.c_str(), p->name(), controller.progress().spp);
      }
    }
    if (o.onSnapshot) o.onSnapshot(controller, true);
    controller.engine().cancel();
  }
  ImGui::DestroyContext();
  return rc;
}

}  // namespace penumbra::ui
