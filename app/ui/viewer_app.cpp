#include "app/ui/viewer_app.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
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
#include "core/image/image_io.h"
#include "core/image/tonemap.h"
#include "core/math/error.h"

namespace penumbra::ui {

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

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
  }

  // One UI frame: fetch the snapshot, upload if new, draw image + panels, present.
  void frame() {
    platform_.pollEvents();
    c_.checkFileChanged();
    bool wantError = c_.display.falseColour == FalseColour::RelativeError || st_.hoverValid;
    if (c_.pollSnapshot(wantError)) {
      display_.upload(c_.snapshot());
      if (c_.compareEnabled()) display_.uploadCompare(c_.compareSnapshot());
    }
    if (c_.compareEnabled() != compareShown_ || c_.compareRestartCount() != compareRestart_) {
      display_.clearCompare();  // never show the other strategy's old image on the right
      if (c_.compareEnabled()) display_.uploadCompare(c_.compareSnapshot());
      compareShown_ = c_.compareEnabled();
      compareRestart_ = c_.compareRestartCount();
    }

    platform_.beginFrame();
    ImGui::NewFrame();
    int fbW = 0, fbH = 0;
    platform_.framebufferSize(fbW, fbH);
    layout_ = layoutImage(c_.display, c_.settings().camera.width, c_.settings().camera.height, kSidebarWidth,
                          std::max(fbW - kSidebarWidth, 1), fbH);
    handleInput();
    display_.dividerX = c_.compareEnabled() ? dividerScreenX() : 0.f;
    drawPanels(fbH);
    if (c_.compareEnabled()) drawCompareLabels();
    ImGui::Render();

    glClearColor(0.16f, 0.16f, 0.17f, 1.f);
    glClear(GL_COLOR_BUFFER_BIT);
    display_.draw(c_.display, layout_, fbW, fbH);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    platform_.endFrame();
    if (st_.requestSavePng) {
      st_.requestSavePng = false;
      try {
        st_.status = c_.saveImage(st_.savePath);
      } catch (const std::exception& e) {
        st_.status = e.what();
      }
    }
  }

  const ImageLayout& layout() const { return layout_; }
  const ImageDisplay& display() const { return display_; }

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
    IntegratorDesc right = c_.compareIntegrator();
    if (right.type == IntegratorType::Direct && !c_.sceneHasAreaLights())
      right.measure = DirectMeasure::Hemisphere;
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
                     ImGuiWindowFlags_NoSavedSettings);
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
};

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

int runBench(platform::Platform& p, ViewerController& c, ViewerApp& app, int frames) {
  const RenderSettings& s = c.settings();
  std::printf("bench: %s, %dx%d, %s, %d worker threads, %s\n", p.name(), s.camera.width, s.camera.height,
              strategyLabel(s.integrator).c_str(), c.engine().threadCount(), p.glRenderer().c_str());
  RenderLimits endless;
  c.setLimits(endless);
  const double seconds = 3.0;

  // 1. The engine alone (what `penumbra render` does): no UI loop, the main thread sleeps.
  c.restart();
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  RenderProgress alone = c.progress();
  double aloneRate = double(alone.samples) / std::max(alone.seconds, 1e-9);

  // 2. The same accumulation with the UI loop running as fast as it can.
  c.restart();
  std::vector<double> frameMs;
  auto t0 = Clock::now();
  while (msSince(t0) < seconds * 1000 || int(frameMs.size()) < frames) {
    auto f0 = Clock::now();
    app.frame();
    frameMs.push_back(msSince(f0));
  }
  RenderProgress withUi = c.progress();
  double uiRate = double(withUi.samples) / std::max(withUi.seconds, 1e-9);

  // 3. Restart latency: a control change (the seed) until a frame shows the new estimate (the
  // engine's coarse preview), and until the first full pass.
  std::vector<double> latency, fullPass;
  for (int i = 0; i < 10; ++i) {
    RenderSettings next = c.settings();
    next.seed += 1;
    auto r0 = Clock::now();
    c.setSettings(next);
    bool shown = false;
    for (;;) {
      app.frame();
      bool current = c.snapshotRestart() == c.restartCount() && !c.snapshot().mean.empty();
      if (current && !shown) {
        latency.push_back(msSince(r0));
        shown = true;
      }
      if (current && c.snapshot().spp >= 1) break;
      if (msSince(r0) > 10000) break;
    }
    if (!shown) latency.push_back(msSince(r0));
    fullPass.push_back(msSince(r0));
    for (int k = 0; k < 5; ++k) app.frame();
  }
  double fm = median(frameMs);
  double lost = 100.0 * (1.0 - uiRate / std::max(aloneRate, 1e-9));
  std::printf("bench: UI frame time median %.2f ms (%.0f fps) over %zu frames, p90 %.2f ms\n", fm,
              1000.0 / fm, frameMs.size(), [&] {
                auto v = frameMs;
                std::sort(v.begin(), v.end());
                return v[v.size() * 9 / 10];
              }());
  std::printf(
      "bench: restart latency (control change -> first frame of the new estimate) median %.1f ms, max %.1f "
      "ms\n",
      median(latency), *std::max_element(latency.begin(), latency.end()));
  std::printf("bench: control change -> first full pass on screen: median %.1f ms\n", median(fullPass));
  std::printf(
      "bench: throughput engine alone %.3f M samples/s, with UI %.3f M samples/s: %.1f %% lost to the UI\n",
      aloneRate * 1e-6, uiRate * 1e-6, lost);
  std::printf("bench: targets >= 60 fps: %s, <= 50 ms: %s, <= 10 %% lost: %s\n",
              1000.0 / fm >= 60 ? "met" : "NOT met", median(latency) <= 50 ? "met" : "NOT met",
              lost <= 10 ? "met" : "NOT met");
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
      rc = runBench(*p, controller, app, std::max(o.frames, 60));
    } else {
      auto t0 = Clock::now();
      for (int frame = 0; !p->shouldClose() && (o.frames <= 0 || frame < o.frames); ++frame) {
        if (o.waitForTarget && o.frames > 0 && frame == o.frames - 1) {
          // Last frame: let the accumulation reach its limit first (bounded wait).
          while ((!controller.progress().finished ||
                  (controller.compareEnabled() && !controller.compareProgress().finished)) &&
                 msSince(t0) < 120000)
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
          app.frame();  // picks up the final snapshot
        }
        app.frame();
      }
      if (o.printLayout) {
        const ImageLayout& l = app.layout();
        std::printf("image-rect %g %g %d %d %g\n", l.x, l.y, l.width, l.height, l.zoom);
        RenderProgress pr = controller.progress();
        std::printf("spp %u restarts %llu\n", pr.spp, (unsigned long long)controller.restartCount());
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
