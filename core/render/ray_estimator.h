// An integrator's estimate along one ray: n camera samples of one sampler, their mean and standard
// error. estimateRayOf (core/render/strategy_dispatch.h) instantiates it per strategy for the
// closed-form tests and the stiff-case catalogue.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/geometry/ray.h"
#include "core/math/float_util.h"
#include "core/render/strategy_dispatch.h"
#include "core/sampling/sampler.h"
#include "core/world/scene.h"

namespace penumbra {

// Runs `integrator.Li(ray)` n times and returns the mean (of the red channel) and its standard error.
// Independent samples: the standard error of the n samples. Other samplers' samples are not
// independent (stratified, nets), so their spread says little about the mean's error: n is split
// into kReplications independently seeded replications of n / kReplications samples (each a
// complete stratification / net), and the standard error comes from the spread of their means.
template <class Integrator>
RayEstimate estimateRay(const Scene& scene, const Integrator& integrator, const Ray& ray, int n,
                        uint64_t seed, SamplerKind kind = SamplerKind::Independent) {
  constexpr int kReplications = 32;
  const bool replicate = kind != SamplerKind::Independent && n >= 2 * kReplications;
  const int groups = replicate ? kReplications : n;
  const int perGroup = replicate ? n / kReplications : 1;
  double sum = 0, sumSq = 0;
  RayEstimate e;
  Sampler independent(SamplerKind::Independent, 1, seed);
  for (int g = 0; g < groups; ++g) {
    Sampler replication(kind, uint32_t(perGroup), hashCombine(seed, uint64_t(g)));
    Sampler& sampler = replicate ? replication : independent;
    double groupSum = 0;
    for (int i = 0; i < perGroup; ++i) {
      sampler.startPixelSample(IVec2(7, 11), uint32_t(replicate ? i : g));
      Color3 L = integrator.Li(scene, ray, sampler);
      if (!isValidRadiance(L)) {
        ++e.bad;
        continue;
      }
      groupSum += L.x;
    }
    const double m = groupSum / perGroup;
    sum += m;
    sumSq += m * m;
  }
  e.mean = sum / groups;
  double var = std::max(0.0, sumSq / groups - e.mean * e.mean) * groups / (groups - 1.0);
  e.standardError = std::sqrt(var / groups);
  return e;
}

}  // namespace penumbra
