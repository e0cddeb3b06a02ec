#include "core/image/tonemap.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

float srgbOetf(float v) {
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.f / 2.4f) - 0.055f;
}

float srgbToLinear(float e) {
  return e <= 0.04045f ? e / 12.92f : std::pow((e + 0.055f) / 1.055f, 2.4f);
}

std::uint8_t toSrgb8(float linear) {
  if (!std::isfinite(linear)) return 0;
  float v = std::clamp(srgbOetf(std::max(linear, 0.f)), 0.f, 1.f);
  return static_cast<std::uint8_t>(v * 255.f + 0.5f);
}

std::vector<std::uint8_t> toSrgb8(const Image& image, float exposureStops) {
  const float scale = std::exp2(exposureStops);
  std::vector<std::uint8_t> out(image.rgb.size());
  for (std::size_t i = 0; i < image.rgb.size(); ++i) {
    float v = image.rgb[i];
    if (!std::isfinite(v)) {
      out[i] = 0;
      continue;
    }
    float t = v * scale;
    if (std::isinf(t)) t = t > 0.f ? 1.f : 0.f;  // finite pixel pushed past FLT_MAX by the exposure
    out[i] = toSrgb8(t);
  }
  return out;
}

}  // namespace penumbra
