// Where the image lands in the viewer's window, and the two questions the mouse asks of it: which
// image pixel is under the cursor, and what the zoom becomes after a wheel step. GL-free.
#pragma once

#include "app/ui/viewer_controller.h"

namespace penumbra::ui {

// Where the image lands in the framebuffer (top-left origin, pixels).
struct ImageLayout {
  float x = 0, y = 0;         // top-left corner of the image
  float zoom = 1;             // screen pixels per image pixel
  int width = 0, height = 0;  // image size in image pixels
};

// The zoom range the display offers (the wheel and the zoom slider); a fitted zoom may be smaller.
inline constexpr float kMinZoom = 1.f / 16, kMaxZoom = 16.f;

// Image placement inside the area [areaX, areaX + areaW) x [0, areaH) for the display settings.
ImageLayout layoutImage(const DisplaySettings& d, int imageW, int imageH, int areaX, int areaW, int areaH);

// The image pixel under screen point (sx, sy), false when there is none. Safe for any layout and
// point: a tiny zoom or a far cursor puts the point outside the image, never beyond an int.
bool imagePixelAt(const ImageLayout& l, float sx, float sy, int& px, int& py);

// The zoom after `wheel` steps of 1.25x from what is on screen (the fitted zoom when fitting),
// within [kMinZoom, kMaxZoom] (or the fitted zoom, when that is already smaller and the wheel zooms
// out). Any wheel value, however large or not finite, gives a zoom in that range.
float zoomAfterWheel(const DisplaySettings& d, float layoutZoom, float wheel);

}  // namespace penumbra::ui
