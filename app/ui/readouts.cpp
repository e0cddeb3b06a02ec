#include "app/ui/readouts.h"

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
