// Dear ImGui's OpenGL3 renderer backend, compiled here against plain GL prototypes.
// libimgui.a ships the same backend with its own loader (imgl3w), which dlopens libGL and therefore
// cannot work under OSMesa. Built with IMGUI_IMPL_OPENGL_LOADER_CUSTOM, this object leaves every gl*
// symbol undefined, so each executable binds it to its own GL library at link time: libGL (GLFW
// window) or libOSMesa (offscreen). No library sources are copied: the file is included from the
// libimgui-dev package by absolute path (IMGUI_BACKENDS_DIR, set by CMake).
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#define IMGUI_IMPL_OPENGL_LOADER_CUSTOM 1
#define PENUMBRA_STR2(x) #x
#define PENUMBRA_STR(x) PENUMBRA_STR2(x)
#include PENUMBRA_STR(IMGUI_BACKENDS_DIR/imgui_impl_opengl3.cpp)
