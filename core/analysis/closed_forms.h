// Closed-form ground truth for tests and `penumbra check`, in double precision with numerically
// careful evaluations (series where a difference of nearly equal terms would cancel).
//
// Notation: shading point x, unit normal n; sphere centre c, radius r; d = |c - x|; sin α = r/d;
// θ = angle between n and (c - x). Irradiance from a uniform sphere light of radiance Le with nothing
// in the way is E = Le · I(θ, α).
#pragma once

#include <glm/glm.hpp>

namespace penumbra {

// I(θ, α) from cos θ and sin α ∈ [0, 1]. cos α is derived as √((1 - sin α)(1 + sin α)); prefer the
// four-argument or geometric overloads when you have a better cos α (near the light's surface).
//   cos θ ≥ sin α (fully above the horizon):  π sin²α cos θ
//   cos θ ≤ -sin α (fully below):             0
//   otherwise (straddling):                   sin²α (cos θ acos y + w) + (atan w - w),
//        y = -cot α cot θ, q = √(1 - y²), w = tan α sin θ q, atan w - w by series for w < 0.1
//   sin α = 1 (x on the surface):             (π/2)(1 + cos θ)
double sphereLightIrradianceFactor(double cosTheta, double sinAlpha);
// Same with all four trig values supplied (no re-derivation; sin²+cos² = 1 assumed).
double sphereLightIrradianceFactor(double cosTheta, double sinTheta, double sinAlpha, double cosAlpha);

// Geometric front end. n need not be normalised. d > r: the formulas above with
// cos α = √(((d - r)/d)((d + r)/d)); |d - r| ≤ 16 ε (r + |x|∞ + |c|∞)
// (rounding of the inputs): x on the surface, (π/2)(1 + cos θ);
// d < r: inside, 0 for a one-sided (outward) emitter and π for a two-sided one.
// If x is at the centre (d = 0) the result is the inside value.
double sphereLightIrradianceFactor(const glm::dvec3& x, const glm::dvec3& n, const glm::dvec3& c, double r,
                                   bool twoSided = false);

// The straddling formula evaluated literally, as written in the reference
//   sin²α cos θ acos y - cos α sin α sin θ q + atan(tan α sin θ q)
// (cancels to O(α³) for small α; exposed for tests comparing it with the stable form).
double sphereLightStraddlingDirect(double cosTheta, double sinTheta, double sinAlpha, double cosAlpha);

// Centre exactly on the horizon (θ = π/2): α - sin α cos α, by series for small α (no cancellation).
double sphereLightHorizonFactor(double alpha);

// atan(w) - w without cancellation (series for |w| < 0.1).
double atanMinusIdentity(double w);

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
