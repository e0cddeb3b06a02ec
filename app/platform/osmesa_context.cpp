// Offscreen OpenGL through OSMesa (llvmpipe, 3.3+ core profile) rendering into a buffer in memory.
// Linked only into penumbra-offscreen, which links libOSMesa and not libGL: every gl* call of the
// viewer and of the ImGui OpenGL3 backend then resolves to OSMesa.
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <vector>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/osmesa.h>
#include <imgui.h>
#include <imgui_impl_opengl3.h>

#include "app/platform/platform.h"
#include "core/math/error.h"

namespace penumbra::platform {

namespace {

class OsMesaContext final : public Platform {
 public:
  explicit OsMesaContext(const WindowOptions& o) : width_(o.width), height_(o.height) {
    // BGRA, the byte order of X11 and Wayland windows: ImageDisplay's textures use it, so that its
    // unscaled image copies are memory copies on both platforms.
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_BGRA,
                           OSMESA_DEPTH_BITS,
                           0,
                           OSMESA_STENCIL_BITS,
                           0,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           3,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           3,
                           0};
    ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!ctx_) throw Error("OSMesa: cannot create an OpenGL 3.3 core context");
    buffer_.assign(size_t(width_) * height_ * 4, 0);
    if (!OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_)) {
      OSMesaDestroyContext(ctx_);
      throw Error("OSMesa: cannot make the context current");
    }
    if (!ImGui_ImplOpenGL3_Init("#version 330 core")) throw Error("OSMesa: ImGui OpenGL3 backend failed");
    ImGuiIO& io = ImGui::GetIO();
    io.BackendPlatformName = "penumbra_osmesa";
    last_ = std::chrono::steady_clock::now();
  }
  ~OsMesaContext() override {
    ImGui_ImplOpenGL3_Shutdown();
    OSMesaDestroyContext(ctx_);
  }
  const char* name() const override { return "OSMesa"; }
  bool offscreen() const override { return true; }
  void framebufferSize(int& w, int& h) const override {
    w = width_;
    h = height_;
  }
  void pollEvents() override {}
  void waitEvents(double seconds) override {  // no events offscreen: only wake() or the timeout
    std::unique_lock lk(wakeMutex_);
    wakeCv_.wait_for(lk, std::chrono::duration<double>(std::max(seconds, 0.0)), [&] { return woken_; });
    woken_ = false;
  }
  void wake() override {
    {
      std::lock_guard lk(wakeMutex_);
      woken_ = true;
    }
    wakeCv_.notify_all();
  }
  bool shouldClose() const override { return false; }
  void beginFrame() override {
    ImGui_ImplOpenGL3_NewFrame();
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(float(width_), float(height_));
    io.DisplayFramebufferScale = ImVec2(1, 1);
    auto now = std::chrono::steady_clock::now();
    io.DeltaTime = std::max(1e-4f, std::chrono::duration<float>(now - last_).count());
    last_ = now;
  }
  void endFrame() override { glFinish(); }
  std::vector<std::uint8_t> readPixels(int& w, int& h) override {
    glFinish();
    w = width_;
    h = height_;
    std::vector<std::uint8_t> rgb(size_t(w) * h * 3);
    for (int y = 0; y < h; ++y) {  // the buffer is bottom-up (OSMESA_Y_UP)
      const std::uint8_t* src = &buffer_[size_t(h - 1 - y) * w * 4];
      std::uint8_t* dst = &rgb[size_t(y) * w * 3];
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) dst[x * 3 + c] = src[x * 4 + 2 - c];  // BGRA
    }
    return rgb;
  }

 private:
  OSMesaContext ctx_ = nullptr;
  int width_, height_;
  std::vector<std::uint8_t> buffer_;
  std::chrono::steady_clock::time_point last_;
  std::mutex wakeMutex_;
  std::condition_variable wakeCv_;
  bool woken_ = false;
};

}  // namespace

bool isOffscreenBuild() {
  return true;
}

bool displayAvailable(std::string& why) {
  why = "offscreen build";
  return false;
}

std::unique_ptr<Platform> createPlatform(const WindowOptions& options) {
  return std::make_unique<OsMesaContext>(options);
}

}  // namespace penumbra::platform
