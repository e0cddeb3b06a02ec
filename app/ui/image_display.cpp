#include "app/ui/image_display.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include "app/ui/divider_columns.h"
#include "app/ui/gl_program.h"
#include "core/math/error.h"
#include "penumbra_shaders.h"  // generated from shaders/

namespace penumbra::ui {

namespace {

GLuint makeTexture() {
  GLuint tex = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return tex;
}

// Float RGB image into a texture (Shader path), reallocating on a size change.
void uploadFloat(GLuint tex, const Image& img) {
  glBindTexture(GL_TEXTURE_2D, tex);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  GLint w = 0, h = 0;
  glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &w);
  glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &h);
  if (w != img.width || h != img.height)
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, img.width, img.height, 0, GL_RGB, GL_FLOAT, img.rgb.data());
  else
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, img.width, img.height, GL_RGB, GL_FLOAT, img.rgb.data());
}

// Clears [x0, x1) x [y0, y1) (top-left origin) to a colour. A scissored clear is a drawn rectangle
// on llvmpipe (~6 ns a pixel): only for thin or rare rectangles.
void clearRect(int fbHeight, int x0, int y0, int x1, int y1, const float* rgb) {
  if (x1 <= x0 || y1 <= y0) return;
  glEnable(GL_SCISSOR_TEST);
  glScissor(x0, fbHeight - y1, x1 - x0, y1 - y0);
  glClearColor(rgb[0], rgb[1], rgb[2], 1.f);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
}

bool isSoftwareRenderer() {
  const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  std::string s = r ? r : "";
  for (const char* name : {"llvmpipe", "softpipe", "swrast", "Software Rasterizer"})
    if (s.find(name) != std::string::npos) return true;
  return false;
}

}  // namespace

const char* tonemapperName(Tonemapper t) {
  return t == Tonemapper::Cpu ? "cpu" : "shader";
}

Tonemapper chooseTonemapper() {
  if (const char* e = std::getenv("PENUMBRA_TONEMAP")) {
    if (std::strcmp(e, "cpu") == 0) return Tonemapper::Cpu;
    if (std::strcmp(e, "shader") == 0) return Tonemapper::Shader;
  }
  return isSoftwareRenderer() ? Tonemapper::Cpu : Tonemapper::Shader;
}

ImageDisplay::ImageDisplay(Tonemapper t) : tonemapper_(t) {
  if (t == Tonemapper::Shader) {
    program_ = linkProgram(shaders::k_display_vert, shaders::k_display_frag, "display");
    glGenVertexArrays(1, &vao_);
  }
}

namespace {

void release(unsigned& texture, unsigned& fbo) {
  if (texture) glDeleteTextures(1, &texture);
  if (fbo) glDeleteFramebuffers(1, &fbo);
  texture = fbo = 0;
}

// (Re)allocates a BGRA8 target of w x h (contents from `pixels`, or undefined) with its framebuffer.
// An unsized GL_RGBA with BGRA data makes Mesa store B8G8R8A8, the byte order of its window
// framebuffers (and of OSMesa's, see osmesa_context.cpp): copies between them are memcpy.
void allocate(unsigned& texture, unsigned& fbo, int& width, int& height, int w, int h, const void* pixels) {
  if (!texture) {
    texture = makeTexture();
    glGenFramebuffers(1, &fbo);
  }
  glBindTexture(GL_TEXTURE_2D, texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, w, h, 0, GL_BGRA, GL_UNSIGNED_BYTE, pixels);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
  GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (status != GL_FRAMEBUFFER_COMPLETE) throw Error("display image: framebuffer incomplete");
  width = w;
  height = h;
}

}  // namespace

ImageDisplay::~ImageDisplay() {
  for (Side& s : sides_) {
    release(s.rgba.texture, s.rgba.fbo);
    release(s.screen.target.texture, s.screen.target.fbo);
    unsigned none = 0;
    release(s.mean, none);
    release(s.stdErr, none);
  }
  for (Solid& solid : solids_) release(solid.texture.texture, solid.texture.fbo);
  if (vao_) glDeleteVertexArrays(1, &vao_);
  if (program_) glDeleteProgram(program_);
}

void ImageDisplay::clearCompare() {
  sides_[1].rgba.width = sides_[1].rgba.height = 0;
  sides_[1].dirty = true;
}

void ImageDisplay::tonemap(Side& s, const FilmSnapshot& snap, const DisplaySettings& d) {
  const Image& mean = snap.mean;
  Target& t = s.rgba;
  const bool resized = t.width != mean.width || t.height != mean.height;
  if (tonemapper_ == Tonemapper::Cpu) {
    if (!table_ || table_->curve() != d.tonemap) table_ = std::make_unique<DisplayLevelTable>(d.tonemap);
    tonemapForDisplay(mean, snap.standardError, d, *table_, PixelOrder::Bgra, s.pixels);
    if (resized) {
      allocate(t.texture, t.fbo, t.width, t.height, mean.width, mean.height, s.pixels.data());
    } else {
      glBindTexture(GL_TEXTURE_2D, t.texture);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
      glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, mean.width, mean.height, GL_BGRA, GL_UNSIGNED_BYTE,
                      s.pixels.data());
    }
  } else {
    if (resized) allocate(t.texture, t.fbo, t.width, t.height, mean.width, mean.height, nullptr);
    if (!s.mean) s.mean = makeTexture(), s.stdErr = makeTexture();
    uploadFloat(s.mean, mean);
    uploadFloat(s.stdErr, snap.standardError.empty() ? Image(1, 1) : snap.standardError);
    glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
    glViewport(0, 0, mean.width, mean.height);
    glUseProgram(program_);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, s.stdErr);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, s.mean);
    glUniform1i(glGetUniformLocation(program_, "uMean"), 0);
    glUniform1i(glGetUniformLocation(program_, "uStdErr"), 1);
    glUniform1f(glGetUniformLocation(program_, "uExposure"), d.exposure);
    glUniform1i(glGetUniformLocation(program_, "uTonemap"), int(d.tonemap));
    glUniform1i(glGetUniformLocation(program_, "uView"), int(d.falseColour));
    glBindVertexArray(vao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
  s.exposure = d.exposure;
  s.tonemap = d.tonemap;
  s.falseColour = d.falseColour;
  ++s.made;
}

// Copies the texture's pixels from (srcX, srcY) on (row 0 = top) to the window rectangle
// [x0, x1) x [y0, y1) (top-left origin), unscaled. Textures hold their top row first, and so do
// Mesa's window framebuffers while the window's GL y runs upwards: the blit is flipped in GL terms,
// not in memory, which is what lets Mesa do it with memcpy.
void ImageDisplay::copyToWindow(const Target& t, int srcX, int srcY, int fbHeight, int x0, int x1, int y0,
                                int y1) {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, t.fbo);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glBlitFramebuffer(srcX, srcY, srcX + (x1 - x0), srcY + (y1 - y0), x0, fbHeight - y0, x1, fbHeight - y1,
                    GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void ImageDisplay::blit(Side& s, const ImageLayout& l, const int* visible, int fbHeight, int x0, int x1,
                        int y0, int y1) {
  if (x1 <= x0 || y1 <= y0) return;
  const int lx = int(l.x), ly = int(l.y);
  if (l.zoom == 1.f) {
    copyToWindow(s.rgba, x0 - lx, y0 - ly, fbHeight, x0, x1, y0, y1);
    return;
  }
  if (tonemapper_ == Tonemapper::Shader) {  // hardware GL: a scaled blit costs nothing
    glEnable(GL_SCISSOR_TEST);
    glScissor(x0, fbHeight - y1, x1 - x0, y1 - y0);
    int w = int(std::lround(s.rgba.width * l.zoom)), h = int(std::lround(s.rgba.height * l.zoom));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, s.rgba.fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBlitFramebuffer(0, 0, s.rgba.width, s.rgba.height, lx, fbHeight - ly, lx + w, fbHeight - ly - h,
                      GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDisable(GL_SCISSOR_TEST);
    return;
  }
  // Software GL: a scaled blit is a drawn rectangle (~6 ns a pixel, every frame). Instead resample
  // the visible part to screen pixels on the CPU when the image or the layout changed (~1 ns a
  // pixel), then copy. Screen pixel x shows image pixel floor((x + 0.5 - l.x) / zoom), as display.frag.
  Screen& sc = s.screen;
  const int vx0 = visible[0], vy0 = visible[1], vx1 = visible[2], vy1 = visible[3];
  if (sc.image != s.made || sc.x0 != vx0 || sc.y0 != vy0 || sc.x1 != vx1 || sc.y1 != vy1 || sc.lx != l.x ||
      sc.ly != l.y || sc.zoom != l.zoom) {
    const int w = vx1 - vx0, h = vy1 - vy0;
    std::vector<int> column(w);
    for (int x = 0; x < w; ++x)
      column[x] = std::clamp(int(std::floor((vx0 + x + 0.5f - l.x) / l.zoom)), 0, s.rgba.width - 1);
    std::vector<std::uint32_t> out(size_t(w) * h);
    for (int y = 0; y < h; ++y) {
      int row = std::clamp(int(std::floor((vy0 + y + 0.5f - l.y) / l.zoom)), 0, s.rgba.height - 1);
      const std::uint32_t* src = &s.pixels[size_t(row) * s.rgba.width];
      std::uint32_t* dst = &out[size_t(y) * w];
      if (y > 0 &&
          row == std::clamp(int(std::floor((vy0 + y - 0.5f - l.y) / l.zoom)), 0, s.rgba.height - 1)) {
        std::memcpy(dst, dst - w, sizeof(std::uint32_t) * w);  // same image row as the screen row above
        continue;
      }
      for (int x = 0; x < w; ++x) dst[x] = src[column[x]];
    }
    Target& t = sc.target;
    if (t.width != w || t.height != h) {
      allocate(t.texture, t.fbo, t.width, t.height, w, h, out.data());
    } else {
      glBindTexture(GL_TEXTURE_2D, t.texture);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
      glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_BGRA, GL_UNSIGNED_BYTE, out.data());
    }
    sc.image = s.made;
    sc.x0 = vx0, sc.y0 = vy0, sc.x1 = vx1, sc.y1 = vy1;
    sc.lx = l.x, sc.ly = l.y, sc.zoom = l.zoom;
  }
  copyToWindow(sc.target, x0 - vx0, y0 - vy0, fbHeight, x0, x1, y0, y1);
}

void ImageDisplay::prepare(const DisplaySettings& d, const FilmSnapshot& left, const FilmSnapshot* right) {
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_SCISSOR_TEST);
  const FilmSnapshot* snaps[2] = {&left, right};
  for (int i = 0; i < 2; ++i) {
    Side& s = sides_[i];
    if (!snaps[i]) continue;
    bool settingsChanged =
        s.exposure != d.exposure || s.tonemap != d.tonemap || s.falseColour != d.falseColour;
    if ((s.dirty || (settingsChanged && s.rgba.width > 0)) && !snaps[i]->mean.empty())
      tonemap(s, *snaps[i], d);
    s.dirty = false;
  }
}

void ImageDisplay::draw(const ImageLayout& l, int fbWidth, int fbHeight, int areaX) {
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glViewport(0, 0, fbWidth, fbHeight);

  // The visible part of the image: its rectangle clipped to the area.
  Side& a = sides_[0];
  const int lx = int(l.x), ly = int(l.y);
  const int v[4] = {std::max(lx, areaX), std::max(ly, 0),
                    std::min(lx + int(std::lround(a.rgba.width * l.zoom)), fbWidth),
                    std::min(ly + int(std::lround(a.rgba.height * l.zoom)), fbHeight)};
  const int vx0 = v[0], vy0 = v[1], vx1 = v[2], vy1 = v[3];
  if (a.rgba.width == 0 || vx1 <= vx0 || vy1 <= vy0) {
    fillRect(fbHeight, areaX, 0, fbWidth, fbHeight, kBackgroundRgb);
    return;
  }
  fillRect(fbHeight, areaX, 0, fbWidth, vy0, kBackgroundRgb);  // the bands around the image
  fillRect(fbHeight, areaX, vy1, fbWidth, fbHeight, kBackgroundRgb);
  fillRect(fbHeight, areaX, vy0, vx0, vy1, kBackgroundRgb);
  fillRect(fbHeight, vx1, vy0, fbWidth, vy1, kBackgroundRgb);
  if (!(dividerX > 0.f)) {
    blit(a, l, v, fbHeight, vx0, vx1, vy0, vy1);
    return;
  }
  // Compare: the left side's image, the divider (a light core in dark outlines), the right side's.
  const DividerColumns d = dividerColumns(dividerX, vx0, vx1);
  blit(a, l, v, fbHeight, vx0, d.leftImageEnd, vy0, vy1);
  clearRect(fbHeight, d.leftImageEnd, vy0, d.coreStart, vy1, kDividerOutlineRgb);
  clearRect(fbHeight, d.coreStart, vy0, d.coreEnd, vy1, kDividerCoreRgb);
  clearRect(fbHeight, d.coreEnd, vy0, d.rightImageStart, vy1, kDividerOutlineRgb);
  Side& b = sides_[1];
  if (b.rgba.width == a.rgba.width && b.rgba.height == a.rgba.height)
    blit(b, l, v, fbHeight, d.rightImageStart, vx1, vy0, vy1);
  else  // the right side has no image yet
    clearRect(fbHeight, d.rightImageStart, vy0, vx1, vy1, kBackgroundRgb);
}

void ImageDisplay::fillRect(int fbHeight, int x0, int y0, int x1, int y1, const float* rgb) {
  if (x1 <= x0 || y1 <= y0) return;
  const int w = x1 - x0, h = y1 - y0;
  std::uint8_t c[4] = {std::uint8_t(rgb[2] * 255.f + 0.5f), std::uint8_t(rgb[1] * 255.f + 0.5f),
                       std::uint8_t(rgb[0] * 255.f + 0.5f), 255};  // BGRA
  std::uint32_t colour;
  std::memcpy(&colour, c, 4);
  auto it = std::find_if(solids_.begin(), solids_.end(), [&](const Solid& q) { return q.bgra == colour; });
  if (it == solids_.end()) it = solids_.insert(solids_.end(), Solid{colour, Target{}});
  Target& t = it->texture;
  if (t.width < w || t.height < h) {  // at least as large as any rectangle filled so far
    int tw = std::max(t.width, w), th = std::max(t.height, h);
    std::vector<std::uint32_t> pixels(size_t(tw) * th, colour);
    allocate(t.texture, t.fbo, t.width, t.height, tw, th, pixels.data());
  }
  copyToWindow(t, 0, 0, fbHeight, x0, x1, y0, y1);
}

}  // namespace penumbra::ui
