// The viewer's window system: the only interface that knows whether frames go to a GLFW window
// (penumbra, linked with libGL) or to an OSMesa buffer in memory (penumbra-offscreen, linked with
// libOSMesa and never libGL). Exactly one implementation is linked into each executable:
// glfw_window.cpp or osmesa_context.cpp.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace penumbra::platform {

struct WindowOptions {
  int width = 1280;
  int height = 800;
  std::string title = "Penumbra";
};

class Platform {
 public:
  virtual ~Platform() = default;
  virtual const char* name() const = 0;
  virtual bool offscreen() const = 0;
  // Drawable size in pixels.
  virtual void framebufferSize(int& width, int& height) const = 0;
  virtual void pollEvents() = 0;
  // Processes pending events, waiting up to `seconds` for one to arrive or for wake().
  virtual void waitEvents(double seconds) = 0;
  // Makes a waitEvents in progress (or the next one) return at once. Callable from any thread.
  virtual void wake() = 0;
  // Input and window events (keys, characters, mouse, scroll, resize, expose, focus, drops) seen so
  // far: the viewer redraws when it changes. Always 0 offscreen.
  virtual std::uint64_t eventCount() const { return 0; }
  virtual bool shouldClose() const = 0;
  // Starts an ImGui frame on the platform side (display size, time step, input).
  virtual void beginFrame() = 0;
  // Presents the frame (swap) or completes it (offscreen).
  virtual void endFrame() = 0;
  // The last drawn frame as RGB8, top row first.
  virtual std::vector<std::uint8_t> readPixels(int& width, int& height) = 0;
  // The window's title (no-op offscreen).
  virtual void setTitle(const std::string&) {}
  // Files dropped onto the window (GLFW only).
  std::function<void(const std::vector<std::string>&)> onDrop;
  // Renderer name reported by GL (for --bench and logs).
  std::string glRenderer() const;
};

// True in the binary built with the OSMesa implementation.
bool isOffscreenBuild();
// Whether a display is available (GLFW: $DISPLAY/$WAYLAND_DISPLAY set and glfwInit succeeds).
bool displayAvailable(std::string& why);
// Creates the window or offscreen context, makes its GL context current and initialises the ImGui
// platform + OpenGL3 renderer backends (ImGui::CreateContext must have been called). Throws
// penumbra::Error on failure.
std::unique_ptr<Platform> createPlatform(const WindowOptions& options);

}  // namespace penumbra::platform
