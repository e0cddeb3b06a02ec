// GLFW window with an OpenGL 3.3 core context (linked with libGL through GLFW/GLX or Wayland EGL).
#include <cstdlib>
#include <vector>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include "app/platform/platform.h"
#include "core/math/error.h"

namespace penumbra::platform {

namespace {

std::string gGlfwError;
void onGlfwError(int, const char* description) {
  gGlfwError = description ? description : "unknown";
}

class GlfwWindow final : public Platform {
 public:
  explicit GlfwWindow(const WindowOptions& o) {
    glfwSetErrorCallback(onGlfwError);
    if (!glfwInit()) throw Error("cannot open a window: " + gGlfwError);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    window_ = glfwCreateWindow(o.width, o.height, o.title.c_str(), nullptr, nullptr);
    if (!window_) {
      glfwTerminate();
      throw Error("cannot create an OpenGL 3.3 core window: " + gGlfwError);
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(1);
    glfwSetWindowUserPointer(window_, this);
    // Every input or window event counts (the viewer redraws only when something happened). These are
    // installed before ImGui's backend, which chains to them from its own callbacks.
    glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double, double) { count(w); });
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int, int, int) { count(w); });
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double) { count(w); });
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int, int, int, int) { count(w); });
    glfwSetCharCallback(window_, [](GLFWwindow* w, unsigned) { count(w); });
    glfwSetCursorEnterCallback(window_, [](GLFWwindow* w, int) { count(w); });
    glfwSetWindowFocusCallback(window_, [](GLFWwindow* w, int) { count(w); });
    glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int, int) { count(w); });
    glfwSetWindowRefreshCallback(window_, [](GLFWwindow* w) { count(w); });
    glfwSetDropCallback(window_, [](GLFWwindow* w, int count, const char** paths) {
      auto* self = static_cast<GlfwWindow*>(glfwGetWindowUserPointer(w));
      ++self->events_;
      if (!self->onDrop) return;
      std::vector<std::string> files(paths, paths + count);
      self->onDrop(files);
    });
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
  }
  ~GlfwWindow() override {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
  const char* name() const override { return "GLFW"; }
  bool offscreen() const override { return false; }
  void framebufferSize(int& w, int& h) const override { glfwGetFramebufferSize(window_, &w, &h); }
  void pollEvents() override { glfwPollEvents(); }
  void waitEvents(double seconds) override {
    if (seconds > 0)
      glfwWaitEventsTimeout(seconds);
    else
      glfwPollEvents();
  }
  void setTitle(const std::string& title) override { glfwSetWindowTitle(window_, title.c_str()); }
  void wake() override { glfwPostEmptyEvent(); }
  std::uint64_t eventCount() const override { return events_; }
  bool shouldClose() const override { return glfwWindowShouldClose(window_); }
  void beginFrame() override {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
  }
  void endFrame() override { glfwSwapBuffers(window_); }
  std::vector<std::uint8_t> readPixels(int& w, int& h) override {
    framebufferSize(w, h);
    std::vector<std::uint8_t> rgb(size_t(w) * h * 3), row(size_t(w) * 3);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
    for (int y = 0; y < h / 2; ++y)  // GL rows are bottom-up
      std::swap_ranges(rgb.begin() + size_t(y) * w * 3, rgb.begin() + size_t(y + 1) * w * 3,
                       rgb.begin() + size_t(h - 1 - y) * w * 3);
    return rgb;
  }

 private:
  static void count(GLFWwindow* w) { ++static_cast<GlfwWindow*>(glfwGetWindowUserPointer(w))->events_; }

  GLFWwindow* window_ = nullptr;
  std::uint64_t events_ = 0;
};

}  // namespace

bool isOffscreenBuild() {
  return false;
}

bool displayAvailable(std::string& why) {
  const char* x = std::getenv("DISPLAY");
  const char* wl = std::getenv("WAYLAND_DISPLAY");
  if ((!x || !*x) && (!wl || !*wl)) {
    why = "no display ($DISPLAY and $WAYLAND_DISPLAY are not set)";
    return false;
  }
  glfwSetErrorCallback(onGlfwError);
  if (!glfwInit()) {
    why = "cannot connect to the display: " + gGlfwError;
    return false;
  }
  glfwTerminate();
  return true;
}

std::unique_ptr<Platform> createPlatform(const WindowOptions& options) {
  return std::make_unique<GlfwWindow>(options);
}

}  // namespace penumbra::platform
