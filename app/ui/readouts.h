// Text of the viewer's readouts that depends on state, kept out of the panels so tests can check it
// without GL: the pixel inspector's error, the zoom label, progress within a pass.
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

// A pass is "slow" once it has run this long: from then on the viewer shows how far it got.
inline constexpr double kSlowPassSeconds = 0.5;
// Seconds the running pass has taken so far.
double passElapsed(const RenderProgress& p);
// Progress within the running pass, for the Stats panel: "pass 1: 120 of 480 rows (25 %), ~9.0 s
// left" once it is slow ("pass 1: no row finished yet (0.8 s)" before its first row); "" otherwise
// (finished, or passes too quick to follow).
std::string passProgressText(const RenderProgress& p);
// Camera samples a second, the running pass's completed rows (`width` samples each) included, so a
// slow first pass does not read 0.
double samplesPerSecond(const RenderProgress& p, int width);

// An image is dimmed once it is left over from before the last restart (a change of strategy,
// camera, ...) for longer than this: a quick restart replaces it before anyone notices.
inline constexpr double kStaleImageSeconds = 0.25;
bool imageIsStale(uint64_t snapshotRestart, uint64_t restartCount, double secondsSinceRestart);

}  // namespace penumbra::ui
