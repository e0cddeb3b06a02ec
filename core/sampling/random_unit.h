// A uniformly distributed unit vector from a std::mt19937 stream (normalised Gaussian triple), for
// tests and benchmarks that need reproducible random directions outside the renderer's samplers.
#pragma once

#include <random>

#include "core/math/vec.h"

namespace penumbra {

inline Vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<float> n;
  for (;;) {
    Vec3 v(n(rng), n(rng), n(rng));
    float l = glm::length(v);
    if (l > 1e-3f) return v / l;
  }
}

}  // namespace penumbra
