#include "app/ui/image_display.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include "app/ui/gl_program.h"
#include "core/math/error.h"
#include "penumbra_shaders.h"  // generated from shaders/

namespace penumbra::ui {

namespace {

constexpr float kDivider[3] = {0.95f, 0.95f, 0.95f};

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

ImageLayout layoutImage(const DisplaySettings& d, int imageW, int imageH, int areaX, int areaW, int areaH) {
  ImageLayout l;
  l.width = imageW;
  l.height = imageH;
  if (imageW <= 0 || imageH <= 0) return l;
  float zoom = d.zoom;
  if (d.fit) {
    float z = std::min(float(areaW) / imageW, float(areaH) / imageH);
    zoom = z >= 1.f ? std::floor(z) : z;  // integer magnification keeps pixels exact
    if (!(zoom > 0.f)) zoom = 1.f;
  }
  l.zoom = zoom;
  l.x = std::round(areaX + (areaW - imageW * zoom) * 0.5f + d.panX);
  l.y = std::round((areaH - imageH * zoom) * 0.5f + d.panY);
  return l;
}

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

ImageDisplay::~ImageDisplay() {
  std::vector<Side*> all = {&sides_[0], &sides_[1]};
  for (Solid& solid : solids_) all.push_back(&solid.texture);
  for (Side* s : all) {
    GLuint tex[3] = {s->rgba, s->mean, s->stdErr};
    glDeleteTextures(3, tex);
    glDeleteFramebuffers(1, &s->fbo);
  }
  if (vao_) glDeleteVertexArrays(1, &vao_);
  if (program_) glDeleteProgram(program_);
}

void ImageDisplay::clearCompare() {
  sides_[1].width = sides_[1].height = 0;
  sides_[1].dirty = true;
}

void ImageDisplay::tonemap(Side& s, const FilmSnapshot& snap, const DisplaySettings& d) {
  const Image& mean = snap.mean;
  if (!s.rgba) {
    s.rgba = makeTexture();
    glGenFramebuffers(1, &s.fbo);
  }
  glBindTexture(GL_TEXTURE_2D, s.rgba);
  const bool resized = s.width != mean.width || s.height != mean.height;
  if (tonemapper_ == Tonemapper::Cpu) {
    if (!table_ || table_->curve() != d.tonemap) table_ = std::make_unique<DisplayLevelTable>(d.tonemap);
    tonemapForDisplay(mean, snap.standardError, d, *table_, PixelOrder::Bgra, pixels_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    if (resized)
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, mean.width, mean.height, 0, GL_BGRA, GL_UNSIGNED_BYTE,
                   pixels_.data());
    else
      glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, mean.width, mean.height, GL_BGRA, GL_UNSIGNED_BYTE,
                      pixels_.data());
  } else if (resized) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, mean.width, mean.height, 0, GL_BGRA, GL_UNSIGNED_BYTE, nullptr);
  }
  if (resized) {
    glBindFramebuffer(GL_FRAMEBUFFER, s.fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, s.rgba, 0);
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) throw Error("display image: framebuffer incomplete");
  }
  if (tonemapper_ == Tonemapper::Shader) {
    if (!s.mean) s.mean = makeTexture(), s.stdErr = makeTexture();
    uploadFloat(s.mean, mean);
    uploadFloat(s.stdErr, snap.standardError.empty() ? Image(1, 1) : snap.standardError);
    glBindFramebuffer(GL_FRAMEBUFFER, s.fbo);
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
  s.width = mean.width;
  s.height = mean.height;
  s.exposure = d.exposure;
  s.tonemap = d.tonemap;
  s.falseColour = d.falseColour;
  ++tonemaps_;
}

// Copies the part of side `s` that falls on the screen rectangle [x0, x1) x [y0, y1) (top-left
// origin, inside the image's rectangle). The texture's row 0 is the image's top row: the window's
// GL y runs the other way, and Mesa stores window framebuffers top row first, so this orientation
// is what lets an unscaled blit be a plain memory copy.
void ImageDisplay::blit(const Side& s, const ImageLayout& l, int fbHeight, int x0, int x1, int y0,
                        int y1) const {
  if (x1 <= x0 || y1 <= y0) return;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, s.fbo);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  const int lx = int(l.x), ly = int(l.y);
  if (l.zoom == 1.f) {
    glBlitFramebuffer(x0 - lx, y0 - ly, x1 - lx, y1 - ly, x0, fbHeight - y0, x1, fbHeight - y1,
                      GL_COLOR_BUFFER_BIT, GL_NEAREST);
  } else {
    glEnable(GL_SCISSOR_TEST);
    glScissor(x0, fbHeight - y1, x1 - x0, y1 - y0);
    int w = int(std::lround(s.width * l.zoom)), h = int(std::lround(s.height * l.zoom));
    glBlitFramebuffer(0, 0, s.width, s.height, lx, fbHeight - ly, lx + w, fbHeight - ly - h,
                      GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glDisable(GL_SCISSOR_TEST);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
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
    if ((s.dirty || (settingsChanged && s.width > 0)) && !snaps[i]->mean.empty()) tonemap(s, *snaps[i], d);
    s.dirty = false;
  }
}

void ImageDisplay::draw(const ImageLayout& l, int fbWidth, int fbHeight, int areaX) {
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glViewport(0, 0, fbWidth, fbHeight);

  // The visible part of the image: its rectangle clipped to the area.
  const Side& a = sides_[0];
  const int lx = int(l.x), ly = int(l.y);
  int vx0 = std::max(lx, areaX), vy0 = std::max(ly, 0);
  int vx1 = std::min(lx + int(std::lround(a.width * l.zoom)), fbWidth);
  int vy1 = std::min(ly + int(std::lround(a.height * l.zoom)), fbHeight);
  if (a.width == 0 || vx1 <= vx0 || vy1 <= vy0) {
    fillRect(fbHeight, areaX, 0, fbWidth, fbHeight, kBackgroundRgb);
    return;
  }
  fillRect(fbHeight, areaX, 0, fbWidth, vy0, kBackgroundRgb);  // the bands around the image
  fillRect(fbHeight, areaX, vy1, fbWidth, fbHeight, kBackgroundRgb);
  fillRect(fbHeight, areaX, vy0, vx0, vy1, kBackgroundRgb);
  fillRect(fbHeight, vx1, vy0, fbWidth, vy1, kBackgroundRgb);
  if (!(dividerX > 0.f)) {
    blit(a, l, fbHeight, vx0, vx1, vy0, vy1);
    return;
  }
  // Compare: screen column x (pixel centre x + 0.5) is the divider line when |x + 0.5 - dividerX| < 1,
  // the right side's image when x + 0.5 >= dividerX, the left side's otherwise.
  int lineStart = int(std::floor(dividerX - 1.5f)) + 1, lineEnd = int(std::ceil(dividerX + 0.5f));
  lineStart = std::clamp(lineStart, vx0, vx1);
  lineEnd = std::clamp(lineEnd, lineStart, vx1);
  blit(a, l, fbHeight, vx0, lineStart, vy0, vy1);
  clearRect(fbHeight, lineStart, vy0, lineEnd, vy1, kDivider);
  const Side& b = sides_[1];
  if (b.width == a.width && b.height == a.height)
    blit(b, l, fbHeight, lineEnd, vx1, vy0, vy1);
  else  // the right side has no image yet
    clearRect(fbHeight, lineEnd, vy0, vx1, vy1, kBackgroundRgb);
}

void ImageDisplay::fillRect(int fbHeight, int x0, int y0, int x1, int y1, const float* rgb) {
  if (x1 <= x0 || y1 <= y0) return;
  const int w = x1 - x0, h = y1 - y0;
  std::uint8_t c[4] = {std::uint8_t(rgb[2] * 255.f + 0.5f), std::uint8_t(rgb[1] * 255.f + 0.5f),
                       std::uint8_t(rgb[0] * 255.f + 0.5f), 255};  // BGRA
  std::uint32_t colour;
  std::memcpy(&colour, c, 4);
  auto it = std::find_if(solids_.begin(), solids_.end(), [&](const Solid& q) { return q.rgba == colour; });
  if (it == solids_.end()) it = solids_.insert(solids_.end(), Solid{colour, Side{}});
  Side& s = it->texture;
  if (s.width < w || s.height < h) {  // (re)allocate, at least as large as the window so far
    if (!s.rgba) {
      s.rgba = makeTexture();
      glGenFramebuffers(1, &s.fbo);
    }
    s.width = std::max(s.width, w);
    s.height = std::max(s.height, h);
    std::vector<std::uint32_t> pixels(size_t(s.width) * s.height, colour);
    glBindTexture(GL_TEXTURE_2D, s.rgba);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, s.width, s.height, 0, GL_BGRA, GL_UNSIGNED_BYTE, pixels.data());
    glBindFramebuffer(GL_FRAMEBUFFER, s.fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, s.rgba, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
  ImageLayout at;
  at.x = float(x0);
  at.y = float(y0);
  blit(s, at, fbHeight, x0, x1, y0, y1);
}

}  // namespace penumbra::ui
