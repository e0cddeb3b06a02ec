// Compiles and links a GLSL program from embedded sources; errors name the shader files.
#pragma once

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

namespace penumbra::ui {

// `name` is the shaders/ file stem (e.g. "display"), used in error messages. Throws penumbra::Error.
GLuint linkProgram(const char* vertexSource, const char* fragmentSource, const char* name);

}  // namespace penumbra::ui
