#include "app/platform/platform.h"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>

namespace penumbra::platform {

std::string Platform::glRenderer() const {
  const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const char* v = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return std::string(r ? r : "?") + ", OpenGL " + (v ? v : "?");
}

}  // namespace penumbra::platform
