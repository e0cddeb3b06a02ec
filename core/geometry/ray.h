// A ray segment o + t·d for t in the open interval (tMin, tMax).
#pragma once

#include <cmath>

#include "core/math/vec.h"

namespace penumbra {

// Convention: d should be unit length, so that t is a distance in world units (SurfaceHit::t, tMax of
// shadow rays set to the distance to a light sample, AO rays bounded by the scene extent). Every
// intersection routine also works with a non-unit d; t is then measured in units of |d|.
// Hits are reported only for tMin < t < tMax. Self-intersection is avoided by offsetting the origin
// (offsetRayOrigin), not by a non-zero tMin, so tMin stays 0 for secondary rays.
struct Ray {
  Vec3 o;
  Vec3 d;
  float tMin = 0.f;
  float tMax = INFINITY;

  Vec3 at(float t) const { return o + t * d; }
};

}  // namespace penumbra
