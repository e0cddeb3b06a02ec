// The projected solid angle of a sphere light's cap above a shading point's horizon, in closed form
// (the irradiance factor I(θ, α): a uniform sphere light of radiance Le with nothing in the way gives
// E = Le · I). Double precision, with the cancellation-free evaluations small and grazing lights need.
//
// Notation: shading point x, unit normal n; sphere centre c, radius r; d = |c - x|; sin α = r/d;
// θ = angle between n and (c - x).
#pragma once

namespace penumbra {

// I(θ, α) from cos θ and sin α ∈ [0, 1]. cos α is derived as √((1 - sin α)(1 + sin α)); prefer the
// four-argument overload when you have a better cos α (near the light's surface).
//   cos θ ≥ sin α (fully above the horizon):  π sin²α cos θ
//   cos θ ≤ -sin α (fully below):             0
//   otherwise (straddling):                   sin²α (cos θ acos y + w) + (atan w - w),
//        y = -cot α cot θ, q = √(1 - y²), w = tan α sin θ q, atan w - w by series for w < 0.1
//   sin α = 1 (x on the surface):             (π/2)(1 + cos θ)
double sphereLightIrradianceFactor(double cosTheta, double sinAlpha);
// Same with all four trig values supplied (no re-derivation; sin²+cos² = 1 assumed).
double sphereLightIrradianceFactor(double cosTheta, double sinTheta, double sinAlpha, double cosAlpha);

// The straddling formula evaluated literally,
//   sin²α cos θ acos y - cos α sin α sin θ q + atan(tan α sin θ q)
// (cancels to O(α³) for small α; exposed for tests comparing it with the stable form).
double sphereLightStraddlingDirect(double cosTheta, double sinTheta, double sinAlpha, double cosAlpha);

// Centre exactly on the horizon (θ = π/2): α - sin α cos α, by series for small α (no cancellation).
double sphereLightHorizonFactor(double alpha);

// atan(w) - w without cancellation (series for |w| < 0.1).
double atanMinusIdentity(double w);

}  // namespace penumbra
