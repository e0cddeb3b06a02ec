// Axis-aligned bounding box. An empty box has min = +inf, max = -inf.
#pragma once

#include <cmath>

#include "core/math/vec.h"

namespace penumbra {

struct Bounds {
  Vec3 min{INFINITY};
  Vec3 max{-INFINITY};

  bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
  void expand(const Vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void expand(const Bounds& b) {
    min = glm::min(min, b.min);
    max = glm::max(max, b.max);
  }
  Vec3 extent() const { return empty() ? Vec3(0.f) : max - min; }
  Vec3 center() const { return empty() ? Vec3(0.f) : 0.5f * (min + max); }
  // Length of the diagonal: an upper bound for any segment inside the box (AO ray length).
  float diagonal() const { return glm::length(extent()); }
  // Largest absolute coordinate: the magnitude of the numbers the scene is made of.
  float maxAbs() const { return empty() ? 0.f : maxComponent(glm::max(absVec(min), absVec(max))); }
};

}  // namespace penumbra
