// Lambert's closed form for a uniform planar polygon light: its projected solid angle Ω⊥ above a
// shading point's horizon, which is the irradiance per unit radiance (E = Le Ω⊥) and the normaliser of
// projected-solid-angle sampling (projected_polygon.h). Double precision; core/analysis's closed forms
// build on it.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "core/lights/polygon_light.h"

namespace penumbra {

// Ω⊥ of the polygon `vertices` (winding order, planar, convex or not) from x with normal n (need not be
// normalised), clipped to x's upper half space. One-sided: it emits towards the side its
// counter-clockwise winding's normal points to, and x behind it or in its plane gets 0.
double polygonLightIrradianceFactor(const glm::dvec3& x, const glm::dvec3& n,
                                    const std::vector<glm::dvec3>& vertices);
// The same for a polygon light's vertices (its emitting side is its n).
double polygonLightIrradianceFactor(const PolygonLight& light, const glm::dvec3& x, const glm::dvec3& n);

}  // namespace penumbra
