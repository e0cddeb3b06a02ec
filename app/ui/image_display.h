// The GL side of the image. Each side (the scene's strategy, and in compare mode the second one) is
// tone mapped into an image-sized RGBA8 texture only when its snapshot or a display setting changed,
// by shaders/display.{vert,frag} (embedded at build time) or, on software GL, by the identical CPU
// loop of display_tonemap.h. Every frame then only copies the visible part of that texture to the
// window (glBlitFramebuffer: a plain copy at zoom 1, nearest-neighbour scaling otherwise).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "app/ui/display_tonemap.h"
#include "app/ui/image_layout.h"
#include "app/ui/viewer_controller.h"

namespace penumbra::ui {

// Colour around the image (and under the panels' window, see ViewerApp::frame).
inline constexpr float kBackgroundRgb[3] = {0.16f, 0.16f, 0.17f};

enum class Tonemapper { Cpu, Shader };
const char* tonemapperName(Tonemapper t);
// Cpu when the current GL context is a software rasteriser (llvmpipe, softpipe, swrast), where a
// per-pixel shader costs the render threads far more CPU than the table-driven loop; Shader on
// hardware GL. The environment variable PENUMBRA_TONEMAP=cpu|shader overrides.
Tonemapper chooseTonemapper();

class ImageDisplay {
 public:
  // Needs a current GL 3.3 core context; throws penumbra::Error on shader errors.
  explicit ImageDisplay(Tonemapper t = chooseTonemapper());
  ~ImageDisplay();
  ImageDisplay(const ImageDisplay&) = delete;
  ImageDisplay& operator=(const ImageDisplay&) = delete;

  // The snapshot of a side (0: the scene's strategy, 1: compare) changed: the next draw tone maps it.
  // An empty snapshot (a restart before its first frame) keeps the previous image on screen.
  void snapshotChanged(int side) { sides_[side].dirty = true; }
  // Forgets the compare image (compare mode turned off or restarted).
  void clearCompare();
  // Framebuffer x of the compare divider (<= 0: no compare view).
  float dividerX = 0.f;
  // Tone maps each side whose snapshot or display settings changed (`right`: the compare side, or
  // null). An empty snapshot keeps the side's previous image.
  void prepare(const DisplaySettings& d, const FilmSnapshot& left, const FilmSnapshot* right);
  // Draws the image area [areaX, fbWidth) x [0, fbHeight): the image per `layout`, kBackgroundRgb
  // around it. Every pixel of the area is written once (no clear first).
  void draw(const ImageLayout& layout, int fbWidth, int fbHeight, int areaX);

  // Fills [x0, x1) x [y0, y1) (top-left origin) with a colour by copying from a texture of that
  // colour: on llvmpipe a copy is a memcpy per row, while a scissored clear is a drawn rectangle.
  void fillRect(int fbHeight, int x0, int y0, int x1, int y1, const float* rgb);

  Tonemapper tonemapper() const { return tonemapper_; }

 private:
  // A texture with a framebuffer reading (and writing) it.
  struct Target {
    unsigned texture = 0, fbo = 0;
    int width = 0, height = 0;  // 0 = nothing yet
  };
  // The part of a side's image on screen, resampled to screen pixels (Cpu path, zoom != 1), and what
  // it was made from.
  struct Screen {
    Target target;
    uint64_t image = 0;  // the side's `made` count
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    float lx = 0, ly = 0, zoom = 0;
  };
  struct Side {
    Target rgba;                        // the display image (BGRA8, row 0 = top)
    unsigned mean = 0, stdErr = 0;      // Shader: the snapshot as float textures
    std::vector<std::uint32_t> pixels;  // Cpu: rgba's contents
    bool dirty = false;
    uint64_t made = 0;     // tone mappings so far
    float exposure = 0.f;  // display settings rgba was made with
    Tonemap tonemap = Tonemap::Srgb;
    FalseColour falseColour = FalseColour::None;
    Screen screen;
  };
  void tonemap(Side& s, const FilmSnapshot& snap, const DisplaySettings& d);
  // Copies [x0, x1) x [y0, y1) (top-left origin, inside the visible image rectangle `visible`) of a
  // side's image, placed and zoomed per `l`, to the window.
  void blit(Side& s, const ImageLayout& l, const int* visible, int fbHeight, int x0, int x1, int y0, int y1);
  void copyToWindow(const Target& t, int srcX, int srcY, int fbHeight, int x0, int x1, int y0, int y1);

  Tonemapper tonemapper_;
  unsigned program_ = 0, vao_ = 0;
  Side sides_[2];
  struct Solid {
    std::uint32_t bgra;  // the colour, BGRA8 little-endian
    Target texture;
  };
  std::vector<Solid> solids_;                 // fillRect's textures, one per colour
  std::unique_ptr<DisplayLevelTable> table_;  // Cpu: for the current tone curve
};

}  // namespace penumbra::ui
