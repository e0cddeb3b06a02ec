#include "app/ui/gl_program.h"

#include <string>

#include "core/math/error.h"

namespace penumbra::ui {

namespace {

GLuint compile(GLenum type, const char* source, const std::string& file) {
  GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &source, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = "";
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    glDeleteShader(s);
    throw Error("shaders/" + file + ": " + log);
  }
  return s;
}

}  // namespace

GLuint linkProgram(const char* vertexSource, const char* fragmentSource, const char* name) {
  GLuint vs = compile(GL_VERTEX_SHADER, vertexSource, std::string(name) + ".vert");
  GLuint fs = compile(GL_FRAGMENT_SHADER, fragmentSource, std::string(name) + ".frag");
  GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = "";
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    glDeleteProgram(program);
    throw Error(std::string("shaders/") + name + ": link failed: " + log);
  }
  return program;
}

}  // namespace penumbra::ui
