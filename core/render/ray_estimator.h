// An integrator's estimate along one ray: n camera samples with independent sample streams, their
// mean and standard error. The strategy table instantiates it per strategy (StrategyRow::estimateRay)
// for the closed-form tests and the stiff-case catalogue.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/geometry/ray.h"
#include "core/render/strategy_table.h"
#include "core/sampling/sampler.h"
#include "core/world/scene.h"

namespace penumbra {

// Runs `integrator.Li(ray)` n times and returns the mean (of the red channel) and its standard error.
template <class Integrator>
RayEstimate estimateRay(const Scene& scene, const Integrator& integrator, const Ray& ray, int n,
                        uint64_t seed) {
  Sampler sampler(SamplerKind::Independent, 1, seed);
  double sum = 0, sumSq = 0;
  RayEstimate e;
  for (int i = 0; i < n; ++i) {
    sampler.startPixelSample(IVec2(7, 11), uint32_t(i));
    Color3 L = integrator.Li(scene, ray, sampler);
    if (!(L.x >= 0.f) || !std::isfinite(L.x)) {
      ++e.bad;
      continue;
    }
    sum += L.x;
    sumSq += double(L.x) * L.x;
  }
  e.mean = sum / n;
  double var = std::max(0.0, sumSq / n - e.mean * e.mean) * n / (n - 1.0);
  e.standardError = std::sqrt(var / n);
  return e;
}

}  // namespace penumbra
