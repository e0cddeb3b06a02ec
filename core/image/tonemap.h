// Display conversion shared by PNG output and the viewer's shader: multiply by 2^exposureStops, apply
// the piecewise sRGB OETF, clamp to [0, 1], round to nearest (uint8(v * 255 + 0.5)).
// NaN and ±Inf map to 0 (black): the film counts non-finite samples separately, so a PNG never hides
// them behind a colour; +Inf is treated as invalid rather than as "very bright".
#pragma once

#include <cstdint>
#include <vector>

#include "core/image/image.h"

namespace penumbra {

// sRGB OETF on a linear value in [0, 1] (no clamping): 12.92 v below 0.0031308, else 1.055 v^(1/2.4) - 0.055.
float srgbOetf(float linear);
// Inverse: sRGB-encoded value in [0, 1] to linear.
float srgbToLinear(float encoded);

// One channel: exposure scale already applied by the caller.
std::uint8_t toSrgb8(float linear);

// Whole image, 3 bytes per pixel, same order as Image::rgb.
std::vector<std::uint8_t> toSrgb8(const Image& image, float exposureStops = 0.f);

}  // namespace penumbra
