// The GL side of the image: float textures holding the film snapshot (mean and standard error) and
// the display shader program (shaders/display.{vert,frag}, embedded at build time).
#pragma once

#include <cstdint>

#include "app/ui/viewer_controller.h"

namespace penumbra::ui {

// Where the image lands in the framebuffer (top-left origin, pixels).
struct ImageLayout {
  float x = 0, y = 0;         // top-left corner of the image
  float zoom = 1;             // screen pixels per image pixel
  int width = 0, height = 0;  // image size in image pixels
};

// Image placement inside the area [areaX, areaX + areaW) x [0, areaH) for the display settings.
ImageLayout layoutImage(const DisplaySettings& d, int imageW, int imageH, int areaX, int areaW, int areaH);

class ImageDisplay {
 public:
  ImageDisplay();  // needs a current GL 3.3 core context; throws penumbra::Error on shader errors
  ~ImageDisplay();
  ImageDisplay(const ImageDisplay&) = delete;
  ImageDisplay& operator=(const ImageDisplay&) = delete;

  // Uploads the snapshot's mean (and standard error when present).
  void upload(const FilmSnapshot& snapshot);
  // Compare mode: the second strategy's snapshot, shown right of the divider.
  void uploadCompare(const FilmSnapshot& snapshot);
  // Forgets the compare image (compare mode turned off or restarted).
  void clearCompare();
  // Framebuffer x of the compare divider (<= 0: no compare view).
  float dividerX = 0.f;
  // Draws the whole framebuffer: background plus the image per `layout` and the display settings.
  void draw(const DisplaySettings& d, const ImageLayout& layout, int fbWidth, int fbHeight) const;
  uint64_t uploads() const { return uploads_; }

 private:
  unsigned program_ = 0, vao_ = 0, mean_ = 0, stdErr_ = 0;
  int meanW_ = 0, meanH_ = 0, errW_ = 0, errH_ = 0;
  unsigned meanB_ = 0, stdErrB_ = 0;
  int meanBW_ = 0, meanBH_ = 0, errBW_ = 0, errBH_ = 0;
  bool hasImage_ = false;
  uint64_t uploads_ = 0;
};

}  // namespace penumbra::ui
