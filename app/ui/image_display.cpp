#include "app/ui/image_display.h"

#include <algorithm>
#include <cmath>
#include <string>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include "app/ui/gl_program.h"
#include "core/math/error.h"
#include "penumbra_shaders.h"  // generated from shaders/

namespace penumbra::ui {

namespace {

void makeTexture(GLuint& tex) {
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  const float zero[3] = {0, 0, 0};
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, 1, 1, 0, GL_RGB, GL_FLOAT, zero);
}

void uploadImage(GLuint tex, const Image& img, int& w, int& h) {
  glBindTexture(GL_TEXTURE_2D, tex);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  if (w != img.width || h != img.height) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, img.width, img.height, 0, GL_RGB, GL_FLOAT, img.rgb.data());
    w = img.width;
    h = img.height;
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, img.width, img.height, GL_RGB, GL_FLOAT, img.rgb.data());
  }
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

ImageDisplay::ImageDisplay() {
  program_ = linkProgram(shaders::k_display_vert, shaders::k_display_frag, "display");
  glGenVertexArrays(1, &vao_);
  makeTexture(mean_);
  makeTexture(stdErr_);
  makeTexture(meanB_);
  makeTexture(stdErrB_);
  meanW_ = meanH_ = errW_ = errH_ = 1;
  meanBW_ = meanBH_ = errBW_ = errBH_ = 1;
}

ImageDisplay::~ImageDisplay() {
  glDeleteTextures(1, &mean_);
  glDeleteTextures(1, &stdErr_);
  glDeleteTextures(1, &meanB_);
  glDeleteTextures(1, &stdErrB_);
  glDeleteVertexArrays(1, &vao_);
  glDeleteProgram(program_);
}

void ImageDisplay::upload(const FilmSnapshot& snapshot) {
  // A restart publishes an empty snapshot: keep showing the previous image until the first pass of
  // the new accumulation arrives (no flash to the background while dragging the camera).
  if (snapshot.mean.empty()) return;
  hasImage_ = true;
  uploadImage(mean_, snapshot.mean, meanW_, meanH_);
  if (!snapshot.standardError.empty()) uploadImage(stdErr_, snapshot.standardError, errW_, errH_);
  ++uploads_;
}

void ImageDisplay::uploadCompare(const FilmSnapshot& snapshot) {
  if (snapshot.mean.empty()) return;
  uploadImage(meanB_, snapshot.mean, meanBW_, meanBH_);
  if (!snapshot.standardError.empty()) uploadImage(stdErrB_, snapshot.standardError, errBW_, errBH_);
}

void ImageDisplay::clearCompare() {
  const Image none(1, 1);
  uploadImage(meanB_, none, meanBW_, meanBH_);
  uploadImage(stdErrB_, none, errBW_, errBH_);
}

void ImageDisplay::draw(const DisplaySettings& d, const ImageLayout& l, int fbWidth, int fbHeight) const {
  glViewport(0, 0, fbWidth, fbHeight);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_SCISSOR_TEST);
  glUseProgram(program_);
  glActiveTexture(GL_TEXTURE3);
  glBindTexture(GL_TEXTURE_2D, stdErrB_);
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, meanB_);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, stdErr_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, mean_);
  glUniform1i(glGetUniformLocation(program_, "uMean"), 0);
  glUniform1i(glGetUniformLocation(program_, "uStdErr"), 1);
  glUniform1i(glGetUniformLocation(program_, "uMeanB"), 2);
  glUniform1i(glGetUniformLocation(program_, "uStdErrB"), 3);
  glUniform1i(glGetUniformLocation(program_, "uCompare"), dividerX > 0.f ? 1 : 0);
  glUniform1f(glGetUniformLocation(program_, "uDividerX"), dividerX);
  glUniform2f(glGetUniformLocation(program_, "uTopLeft"), l.x, float(fbHeight) - l.y);
  glUniform1f(glGetUniformLocation(program_, "uZoom"), l.zoom);
  glUniform1f(glGetUniformLocation(program_, "uExposure"), d.exposure);
  glUniform1i(glGetUniformLocation(program_, "uTonemap"), int(d.tonemap));
  glUniform1i(glGetUniformLocation(program_, "uView"), int(d.falseColour));
  glUniform1i(glGetUniformLocation(program_, "uHasImage"), hasImage_ ? 1 : 0);
  glUniform3f(glGetUniformLocation(program_, "uBackground"), 0.16f, 0.16f, 0.17f);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace penumbra::ui
