// The false-colour map of the "MIS light share" view: the light technique's share of a pixel's
// area-light estimate (core/integrators/mis_light_share.h: lightShare) to an sRGB colour. Diverging,
// because 1/2 (both techniques contribute equally) is the meaningful middle: blue at 0 (all from
// cosine-hemisphere sampling) through near-white at 1/2 to red at 1 (all from light sampling), the
// end and middle colours of ColorBrewer's RdBu scheme; pixels with no area light to share are dark grey,
// a colour the map never takes (the sky, full shadow, and the lights themselves:
// core/integrators/mis_light_share.h counts a light seen directly as having no share). shaders/display.frag
// computes the same (uView 3).
#pragma once

#include <cmath>
#include <cstdint>

#include "core/image/image.h"
#include "core/image/tonemap.h"
#include "core/integrators/mis_light_share.h"

namespace penumbra::ui {

inline constexpr std::uint8_t kShareZeroRgb[3] = {33, 102, 172};  // all from cosine-hemisphere sampling
inline constexpr std::uint8_t kShareHalfRgb[3] = {247, 247, 247};
inline constexpr std::uint8_t kShareOneRgb[3] = {178, 24, 43};  // all from light sampling
inline constexpr std::uint8_t kNoShareRgb[3] = {64, 64, 64};    // no area light in the pixel

// The map's sRGB colour of a share in [0, 1]; a negative share (none) gives kNoShareRgb.
inline void lightShareRgb(float share, std::uint8_t out[3]) {
  if (!(share >= 0.f)) {
    for (int c = 0; c < 3; ++c) out[c] = kNoShareRgb[c];
    return;
  }
  const float t = share < 0.5f ? 2.f * share : 2.f * share - 1.f;
  const std::uint8_t* a = share < 0.5f ? kShareZeroRgb : kShareHalfRgb;
  const std::uint8_t* b = share < 0.5f ? kShareHalfRgb : kShareOneRgb;
  for (int c = 0; c < 3; ++c)
    out[c] = std::uint8_t(std::floor(float(a[c]) + (float(b[c]) - a[c]) * t + 0.5f));
}

// The map of a light-share film's mean as a linear image whose sRGB encoding (toSrgb8, the PNG writer)
// gives exactly the map's colours: each level decoded exactly (the middle of its rounding interval).
inline Image lightShareMapImage(const Image& mean) {
  Image out(mean.width, mean.height);
  for (int y = 0; y < mean.height; ++y)
    for (int x = 0; x < mean.width; ++x) {
      std::uint8_t rgb[3];
      lightShareRgb(lightShare(mean.at(x, y)), rgb);
      out.set(
          x, y,
          Color3(srgbToLinear(rgb[0] / 255.f), srgbToLinear(rgb[1] / 255.f), srgbToLinear(rgb[2] / 255.f)));
    }
  return out;
}

}  // namespace penumbra::ui
