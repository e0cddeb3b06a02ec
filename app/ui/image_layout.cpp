#include "app/ui/image_layout.h"

#include <algorithm>
#include <cmath>

namespace penumbra::ui {

ImageLayout layoutImage(const DisplaySettings& d, int imageW, int imageH, int areaX, int areaW, int areaH) {
  ImageLayout l;
  l.width = imageW;
  l.height = imageH;
  if (imageW <= 0 || imageH <= 0) return l;
  float zoom = d.zoom;
  if (d.fit) {
    float z = std::min(float(areaW) / imageW, float(areaH) / imageH);
    zoom = z >= 1.f ? std::floor(z) : z;  // integer magnification keeps pixels exact
  }
  if (!(zoom > 0.f) || !std::isfinite(zoom)) zoom = 1.f;
  l.zoom = zoom;
  l.x = std::round(areaX + (areaW - imageW * zoom) * 0.5f + d.panX);
  l.y = std::round((areaH - imageH * zoom) * 0.5f + d.panY);
  return l;
}

bool imagePixelAt(const ImageLayout& l, float sx, float sy, int& px, int& py) {
  if (!(l.zoom > 0.f)) return false;
  // Compared as floats first: the quotient may be far beyond an int (or NaN).
  const float fx = std::floor((sx - l.x) / l.zoom), fy = std::floor((sy - l.y) / l.zoom);
  if (!(fx >= 0.f && fy >= 0.f && fx < float(l.width) && fy < float(l.height))) return false;
  px = int(fx);
  py = int(fy);
  return true;
}

float zoomAfterWheel(const DisplaySettings& d, float layoutZoom, float wheel) {
  const float from = d.fit ? layoutZoom : d.zoom;
  if (!(from > 0.f) || !std::isfinite(from)) return 1.f;
  if (!std::isfinite(wheel)) wheel = 0.f;
  const float lowest = std::min(kMinZoom, from);
  // The power is taken in log space: 1.25^wheel itself under- or overflows for a large wheel.
  const float logZoom = std::log2(from) + std::clamp(wheel, -1000.f, 1000.f) * std::log2(1.25f);
  return std::clamp(std::exp2(std::clamp(logZoom, -126.f, 127.f)), lowest, kMaxZoom);
}

}  // namespace penumbra::ui
