// Projected-solid-angle sampling of a sphere light: directions towards the light distributed in
// proportion to cos θ over the part of its subtended cap above the shading point's horizon, with
// density cos θ / Ω⊥ (Ω⊥ that part's projected solid angle, the closed form of sphere_cap.h).
// For an unoccluded diffuse receiver every sample's estimate Le cos θ / pdf is Le Ω⊥: zero variance.
//
// Nusselt: a direction (x, y, z) of the hemisphere around the normal projects to the point (x, y) of
// the unit disk, and cos θ dω = dx dy, so points uniform in the cap's projection, lifted by
// z = √(1 − x² − y²), are cos-distributed. With x along the projection of the light's centre, a cap of
// angular radius α whose centre is at angle θ from the normal projects to the ellipse of centre
// (cos α sin θ, 0) and semi-axes sin α cos θ (along x) and sin α (along y). A cap straddling the
// horizon projects to a region bounded by the ellipse's arc above the horizon and the unit circle:
// the ellipse touches the circle at the tangent points x = cos α / sin θ, |y| = yTangent, and beyond
// them (x > cos α / sin θ) the region is the whole disk if the centre is above the horizon, the part
// of the disk outside the ellipse if it is below. Every slice y = const of the region is one interval.
//
// The map of the unit square onto the region is a bijection that keeps stratification (no rejection):
//   above the horizon: the concentric disk map scaled onto the ellipse, in closed form;
//   straddling, centre on or above the horizon: the region is two cut disks side by side, the
//   ellipse's part with x ≤ cos α / sin θ and the unit disk's segment beyond it (their x-slices are the
//   ellipse's and the circle's chords, of equal length 2 yTangent where they meet). u.x sets x by
//   inverting the area left of it, which on either piece is a circular segment's area, inverted
//   without iteration (circular_segment.h: to 5e-13 of it); u.y places y uniformly on the chord at x;
//   straddling, centre below the horizon (a lens between the ellipse's outer arc and the circle, whose
//   x-slices would be two intervals): u.x sets y by inverting the region's area below height |y|
//   (Halley's method in the ellipse's angle φ, y = b sin φ, from a cubic model's root, with a
//   bisection fallback, to 1e-10 of the half area (see kAreaTolerance), at most 40 steps, 1.5–2.3 area
//   evaluations on average), u.y places x uniformly on the slice at y.
// Both straddling maps are parallel maps (Ureña & Georgiev, EGSR 2018), along x and along y.
// Plain data, built once per (shading point, light) and reused for every sample there.
#pragma once

#include "core/lights/light_sample.h"
#include "core/lights/sphere_light.h"

namespace penumbra {

struct ProjectedSphereCap {
  // Stop rule of the lens map's inversion: |area below y − target| ≤ inversionTolerance =
  // max(kAreaTolerance · halfArea, 32 ε yMax (k + |a| b), an estimate of the area's rounding) — the
  // sampled y's CDF is then off by at most 1e-10: 600 times finer than the CDF's own quantisation by a
  // float u (2^-24), and a bias that 10^20 samples could not resolve. Only for the thin lenses of a cap just
  // below the horizon, whose area cancels (as does Ω⊥'s closed form), is the rounding floor larger: 6e-8 of
  // the half area at cos θ = −0.999 sin α (Ω⊥ ≈ 1e-8 sin²α), 2e-3 at −0.999995 sin α (Ω⊥ < 1e-13 sin²α). A
  // Halley step is accepted without evaluating the area again where Taylor's bound on its residual is below
  // half the tolerance: the quadratic model's residual f³A''²/(2A'² − fA'')² (exact for the step) plus
  // M₃|δ|³/6, M₃ a bound on |A'''| over the whole range (areaThirdDerivativeBound). Stops also where the step
  // or the bracket shrinks to a few ulps, or after kMaxInversionSteps steps.
  static constexpr double kAreaTolerance = 1e-10;
  static constexpr int kMaxInversionSteps = 40;
  // Below this Ω⊥ the pdf cos θ / Ω⊥ could exceed float's range: nothing is sampled.
  static constexpr double kMinProjectedSolidAngle = 0x1p-120;
  // Float directions carry ~2^-24 relative error per component (see SphereLight::pdfSolidAngle).
  static constexpr double kDirectionSlack = 0x1p-22;

  // Plain data without default values (a cap is constructed per shading point and light; default
  // values would fill it twice): init() sets the fields of the map it chooses when it returns true
  // (the cut-disk fields only for Map::CutDisks, yMax to startCubic only for Map::Lens); after false only
  // projectedSolidAngle = invProjectedSolidAngle = 0, map = Map::Ellipse and straddling = false.
  // The light as seen from the shading point.
  DVec3 origin;    // the shading point x
  DVec3 toCenter;  // c − x
  double radius, distance;
  Color3 radiance;
  // Frame: ez the shading normal, ex towards the projection of the light's centre, ey = ez × ex.
  DVec3 ex, ey, ez;
  double sinAlpha, cosAlpha;    // the cap's angular radius
  double cosCentre, sinCentre;  // angle of the cap's centre from the normal
  // The projected region: ellipse centre (xc, 0), semi-axis a along x (sin α cos θ, negative when the
  // centre is below the horizon) and b = sin α along y; k = 1 − xc² (= sin²α + cos²α cos²θ, computed
  // so: the lift z² = k − y² − δx (2 xc + δx) at x = xc + δx has no cancellation for small caps).
  double xc, a, b, k;
  enum class Map : unsigned char { Ellipse, CutDisks, Lens };
  Map map;
  bool straddling;  // map != Ellipse
  double yTangent;  // |y| of the tangent points (straddling)
  // Map::CutDisks: the ellipse piece's area a b g(βt) and 1 / (a b) (g, βt: circular_segment.h, the
  // angle in the ellipse's own unit disk at which the tangent points lie).
  double ellipsePieceArea, invAB;
  // Map::Lens:
  double yMax;              // the region's largest |y|
  double gTangent;          // G(yTangent / b) (see areaBelow)
  double areaBelowTangent;  // areaBelow(yTangent)
  double halfArea;  // areaBelow(yMax): the area of the region's y ≥ 0 half, as the map integrates it
  double inversionTolerance;
  double invB;
  double phiTangent, cosPhiTangent, phiMax;  // the ellipse's angle: y = b sin φ
  double areaThirdDerivativeBound;           // M₃ ≥ |d³A/dφ³| on [0, phiMax]
  double startWidth, invStartWidth,
      startCubic;  // the inversion's first guess: sliceWidth(0), its cubic model
  // Ω⊥, the pdf's normalisation: the map's own area (π a b above the horizon, the two pieces' areas
  // for cut disks, 2 halfArea for the lens), sphere_cap.h's closed form to rounding.
  double projectedSolidAngle;
  double invProjectedSolidAngle;

  // Sets up the cap of `light` seen from x with unit normal n. False (nothing to sample) when x is
  // inside the light, the light is degenerate, nothing of it is above the horizon, or Ω⊥ < 2^-120
  // (its pdf would not fit a float). x on the surface: the hemisphere towards the centre.
  bool init(const SphereLight& light, const Vec3& x, const Vec3& n);

  struct Direction {
    DVec3 w;          // unit, world space
    double cosTheta;  // dot(ez, w) ≥ 0
  };
  // The map of the unit square, in double (the χ² tests bin it in the cap's own frame).
  Direction sampleDirection(Vec2 u) const;
  // A sample for the estimator: direction, the point where it meets the light, pdf = cos θ / Ω⊥.
  // Its estimate factor cos θ / pdf is projectedSolidAngle exactly.
  LightSample sample(Vec2 u) const;
  // Density of sampleDirection w.r.t. solid angle: cos θ / Ω⊥ inside the visible cap, 0 outside. w in
  // double, need not be unit; exact cap test.
  double pdfDirection(const DVec3& w) const;
  // The same for a float direction (as the estimators hold them): the cap test allows sin γ up to
  // sin α + 2^-22 (a float direction's rounding), as SphereLight::pdfSolidAngle does.
  float pdf(const Vec3& w) const;

  // The lens map's parts (Map::Lens only; 0 ≤ y ≤ yMax). areaBelow(y): the area of the
  // region's part with 0 ≤ y' ≤ y, in closed form; sliceWidth(y): its derivative.
  struct Slice {
    double area, width, slope;  // areaBelow(y), sliceWidth(y), d sliceWidth / dy
  };
  Slice slice(double y) const;
  double areaBelow(double y) const;
  double sliceWidth(double y) const;
  struct Inversion {
    double y;
    int steps;
    double cosPhi;  // √(1 − y²/b²)
  };
  // y with areaBelow(y) = target ∈ [0, halfArea], to the stop rule above.
  Inversion invertArea(double target) const;

 private:
  void initCutDisks(double invSinCentre);  // 1 / sin θ
  void initLens();
  struct ArcSlice {
    double area, dArea, d2Area;  // areaBelow(b sin φ) and its derivatives in φ
  };
  ArcSlice arcSlice(double phi, double sinPhi, double cosPhi) const;
  double circleGap(double y, double s1) const;
};

}  // namespace penumbra
