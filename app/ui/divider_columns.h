// The compare divider's columns on screen, without GL: a light core with a dark outline on each
// side, so the line stands out over a white floor as over a black sky.
#pragma once

#include <algorithm>
#include <cmath>

namespace penumbra::ui {

inline constexpr float kDividerCoreRgb[3] = {0.95f, 0.95f, 0.95f};
inline constexpr float kDividerOutlineRgb[3] = {0.05f, 0.05f, 0.05f};

// Screen columns [x0, x1) of each part, clipped to the visible image [vx0, vx1): the left image, the
// left outline, the core, the right outline, the right image, in that order and adjacent.
struct DividerColumns {
  int leftImageEnd, coreStart, coreEnd,
      rightImageStart;  // outlines: [leftImageEnd, coreStart), [coreEnd, rightImageStart)
};

// The core is the 2 columns whose centres lie within 1 px of `dividerX`, each outline 1 column.
inline DividerColumns dividerColumns(float dividerX, int vx0, int vx1) {
  int coreStart = int(std::floor(dividerX - 1.5f)) + 1, coreEnd = int(std::ceil(dividerX + 0.5f));
  coreStart = std::clamp(coreStart, vx0, vx1);
  coreEnd = std::clamp(coreEnd, coreStart, vx1);
  return DividerColumns{std::max(coreStart - 1, vx0), coreStart, coreEnd, std::min(coreEnd + 1, vx1)};
}

}  // namespace penumbra::ui
