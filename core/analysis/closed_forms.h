// Closed-form ground truth for tests and `penumbra check`, in double precision with numerically
// careful evaluations (series where a difference of nearly equal terms would cancel).
//
// Notation: shading point x, unit normal n; sphere centre c, radius r; d = |c - x|; sin α = r/d;
// θ = angle between n and (c - x). Irradiance from a uniform sphere light of radiance Le with nothing
// in the way is E = Le · I(θ, α).
#pragma once

#include <glm/glm.hpp>

#include "core/lights/polygon_lambert.h"  // Ω⊥ of a polygon light (Lambert)
#include "core/lights/sphere_cap.h"       // I(θ, α) from angles, and its building blocks

namespace penumbra {

// The closed form from geometry (sphereLightIrradianceFactor of core/lights/sphere_cap.h from angles).
// n need not be normalised. d > r: I(θ, α) with
// cos α = √(((d - r)/d)((d + r)/d)); |d - r| ≤ 16 ε (r + |x|∞ + |c|∞)
// (rounding of the inputs): x on the surface, (π/2)(1 + cos θ);
// d < r: inside, 0 for a one-sided (outward) emitter and π for a two-sided one.
// If x is at the centre (d = 0) the result is the inside value.
double sphereLightIrradianceFactor(const glm::dvec3& x, const glm::dvec3& n, const glm::dvec3& c, double r,
                                   bool twoSided = false);

// ---- Ambient occlusion, AO = (1/π) ∫ V cos dω with unbounded rays ----------------------------------

// Point on an infinite plane (normal n) with one sphere as the only occluder: 1 - I(θ, α)/π; covers
// spheres that cut the plane. x inside the sphere is fully occluded (0).
double aoPlaneWithSphere(const glm::dvec3& x, const glm::dvec3& n, const glm::dvec3& c, double r);
double aoPlaneWithSphere(double cosTheta, double sinAlpha);

// Plane point at horizontal distance rho from the contact point of a sphere of radius R resting on the
// plane: 1 - R³/(ρ² + R²)^{3/2}, as -expm1(-1.5 log1p(ρ²/R²)) for ρ < R.
double aoPlaneNearRestingSphere(double rho, double R);

// Point on a sphere (or any convex body) resting on an infinite plane, psi = angle of its normal from
// "up" (0 = top, π = contact point): cos²(ψ/2), independent of size.
double aoOnRestingConvexBody(double psi);

}  // namespace penumbra
