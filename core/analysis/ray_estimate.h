// Per-point Monte Carlo estimates of an integrator with their standard error (estimateRay, from
// core/render/ray_estimator.h) and the rays that reach a point: the shared helpers of the
// closed-form tests (estimators_closed_form_test.cpp) and the stiff-case catalogue (`penumbra check`).
#pragma once

#include <glm/geometric.hpp>

#include "core/geometry/ray.h"
#include "core/render/ray_estimator.h"

namespace penumbra::analysis {

using Estimate = RayEstimate;
using ::penumbra::estimateRay;  // core/render/ray_estimator.h

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
