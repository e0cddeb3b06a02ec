// Per-point Monte Carlo estimates of an integrator with their standard error: the shared helper of
// the closed-form tests (estimators_closed_form_test.cpp) and the stiff-case catalogue
// (`penumbra check`).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/geometry/ray.h"
#include "core/sampling/sampler.h"
#include "core/world/scene.h"

namespace penumbra::analysis {

struct Estimate {
  double mean = 0, standardError = 0;
  uint64_t bad = 0;  // NaN / Inf / negative values seen (excluded from the mean)
};

// Runs `integrator.Li(ray)` n times with independent sample streams and returns the mean (of the
// red channel) and its standard error.
template <class Integrator>
Estimate estimateRay(const Scene& scene, const Integrator& integrator, const Ray& ray, int n, uint64_t seed) {
  Sampler sampler(SamplerKind::Independent, 1, seed);
  double sum = 0, sumSq = 0;
  Estimate e;
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

// A ray that hits point `x` coming straight down the normal `n` from a little above.
inline Ray rayOnto(const Vec3& x, const Vec3& n, float height) {
  Ray r;
  r.o = x + n * height;
  r.d = -n;
  return r;
}

// Reaches x on the plane z = 0 at a shallow angle (rising `slope` per unit backwards along -x), so
// the camera ray passes under a light that nearly touches the plane instead of through it.
inline Ray shallowRayOnto(const Vec3& x, float slope = 1e-4f) {
  Ray r;
  r.o = x + Vec3(-1.f, 0.f, slope);
  r.d = glm::normalize(x - r.o);
  return r;
}

}  // namespace penumbra::analysis
