#include "app/ui/readouts.h"

#include <algorithm>
#include <cstdio>

namespace penumbra::ui {

bool probeHasError(uint32_t spp) {
  return spp >= 2;
}

std::string probeErrorText(uint32_t spp, float standardError) {
  if (!probeHasError(spp)) return "(no error estimate below 2 spp)";
  char buf[48];
  std::snprintf(buf, sizeof buf, "± %.2g", standardError);
  return buf;
}

std::string zoomLabel(const DisplaySettings& d, float layoutZoom) {
  char buf[48];
  if (d.fit)
    std::snprintf(buf, sizeof buf, "fit %.3gx", layoutZoom);
  else
    std::snprintf(buf, sizeof buf, "%.3gx", d.zoom);
  return buf;
}

}  // namespace penumbra::ui

namespace penumbra::ui {

double passElapsed(const RenderProgress& p) {
  return std::max(0.0, p.seconds - p.passSeconds);
}

std::string passProgressText(const RenderProgress& p) {
  const double elapsed = passElapsed(p);
  if (p.finished || p.rows == 0 || elapsed < kSlowPassSeconds) return "";
  char buf[160];
  if (p.passRows == 0) {
    std::snprintf(buf, sizeof buf, "pass %u: no row finished yet (%.1f s)", p.spp + 1, elapsed);
    return buf;
  }
  int n = std::snprintf(buf, sizeof buf, "pass %u: %u of %u rows (%.0f %%)", p.spp + 1, p.passRows, p.rows,
                        100.0 * p.passRows / p.rows);
  if (p.passRows < p.rows)
    std::snprintf(buf + n, sizeof buf - n, ", ~%.1f s left", elapsed * (p.rows - p.passRows) / p.passRows);
  return buf;
}

double samplesPerSecond(const RenderProgress& p, int width) {
  if (!(p.seconds > 0)) return 0.0;
  return (double(p.samples) + double(p.passRows) * std::max(width, 0)) / p.seconds;
}

bool imageIsStale(uint64_t snapshotRestart, uint64_t restartCount, double secondsSinceRestart) {
  return snapshotRestart != restartCount && secondsSinceRestart >= kStaleImageSeconds;
}

}  // namespace penumbra::ui
