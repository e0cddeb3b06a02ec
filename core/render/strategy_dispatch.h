// From a strategy's description to its concrete integrator, once per render or per one-ray
// estimate: a nested switch over the axes that apply, each level a compile-time constant below it,
// so the per-sample code of every combination is its own template instance (no per-sample dispatch).
#pragma once

#include <cstdint>

#include "core/integrators/integrator_desc.h"
#include "core/sampling/sampler.h"

namespace penumbra {

struct Ray;
struct Scene;

// Mean (of the red channel) +- standard error of an integrator along one ray (core/render/ray_estimator.h).
struct RayEstimate {
  double mean = 0, standardError = 0;
  uint64_t bad = 0;  // NaN / Inf / negative values seen (excluded from the mean)
};

// n camera samples of `desc`'s integrator along one ray. MIS takes desc.samples as both its counts
// (the tests and the stiff catalogue run one of each).
RayEstimate estimateRayOf(const IntegratorDesc& desc, const Scene& scene, const Ray& ray, int n,
                          uint64_t seed, SamplerKind sampler = SamplerKind::Independent);

}  // namespace penumbra
