#include "app/ui/panel_layout.h"

#include <algorithm>

namespace penumbra::ui {

int minSidebarWidth(int windowWidth) {
  return std::min(200, std::max(windowWidth, 0));
}

int defaultSidebarWidth(int windowWidth) {
  const int wanted = std::clamp(windowWidth * 5 / 16, 260, 560);
  return std::max(std::min(wanted, windowWidth * 2 / 5), minSidebarWidth(windowWidth));
}

int maxSidebarWidth(int windowWidth) {
  return std::max(windowWidth - 160, minSidebarWidth(windowWidth));
}

float labelColumnWidth(int sidebarWidth) {
  return std::clamp(0.42f * float(sidebarWidth), 112.f, 150.f);
}

}  // namespace penumbra::ui
