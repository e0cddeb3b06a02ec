// Text of the viewer's readouts that depends on state, kept out of the panels so tests can check it
// without GL: the pixel inspector's error, the zoom label.
#pragma once

#include <cstdint>
#include <string>

#include "app/ui/viewer_controller.h"

namespace penumbra::ui {

// "± 0.012" for one channel's standard error, or "(no error estimate below 2 spp)" when the
// accumulation has fewer than two samples per pixel (the sample variance is undefined there).
std::string probeErrorText(uint32_t spp, float standardError);
bool probeHasError(uint32_t spp);

// The zoom the image is drawn at: "fit 0.83x" while it follows the window (layoutZoom is what the
// layout computed), else the user's "2x".
std::string zoomLabel(const DisplaySettings& d, float layoutZoom);

}  // namespace penumbra::ui
