// Samples of lights as seen from a shading point x: LightSample (area lights), DeltaLightSample
// (point and directional lights).
#pragma once

#include "core/math/vec.h"

namespace penumbra {

// Validity: pdf == 0 means "no sample" (x inside a one-sided light, a degenerate light, a cone too
// narrow for float): the estimator adds 0 for it. A valid sample may still carry Le == 0 (area
// sampling hit the far side of the light): it contributes 0, which is what keeps the area estimator
// unbiased. Always test `pdf > 0 && !isBlack(Le)` before tracing a shadow ray.
struct LightSample {
  Vec3 p{0.f};       // point on the light
  Vec3 n{0.f};       // light's unit outward normal at p
  Vec3 wi{0.f};      // unit direction from the shading point x toward p
  float dist = 0.f;  // |p − x|; the shadow ray is (x, wi) with tMax slightly below dist
  float pdf = 0.f;   // density of wi with respect to solid angle at x (see each sampler)
  Color3 Le{0.f};    // radiance leaving p toward x
};

// A deterministic sample of a delta light at a shading point x.
struct DeltaLightSample {
  Vec3 wi{0.f};      // unit direction from x toward the light
  float dist = 0.f;  // distance to the light (INFINITY for directional lights)
  // Incident "radiance-like" quantity: irradiance on a surface facing the light, so that
  // E = Li · max(0, dot(n, wi)) · V(x, wi, dist) and diffuse Lr = albedo/π · E.
  Color3 Li{0.f};
};

}  // namespace penumbra
