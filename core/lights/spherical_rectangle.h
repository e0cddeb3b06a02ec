// Uniform solid-angle sampling of a rectangle light: directions uniform over the spherical rectangle it
// subtends at a point x, density 1 / Ω, as a bijection from the unit square (Ureña, Fajardo & King,
// "An Area-Preserving Parametrization for Spherical Rectangles", EGSR 2013), on either side of it.
//
// In the rectangle's frame (x at the origin, the rectangle [a0, a1] × [b0, b1] at distance h) the
// solid angle of the strip [0, A] × [b0, b1] is Φ(A) = arg((h r₁ + i A b1) conj(h r₀ + i A b0)),
// r_j = |(A, b_j, h)|, and inverts in closed form: with θ_j = atan(b_j / h), Δ = θ1 − θ0, σ = θ0 + θ1,
//     A = h sin φ / √((cos φ − cos Δ)(cos φ + cos σ)),
// both factors formed as (1 ∓ cos) − 2 sin²(φ/2) (Ureña's equations, rearranged to avoid their
// cancellation for small rectangles). u.x chooses the column A with Φ(A) = Φ(a0) + u.x Ω; along it
// the solid angle below B grows as t(B) = B / √(A² + h² + B²), and t(B) is linear in u.y. Ω is Van
// Oosterom & Strackee's for the two halves, from the corners' coordinates (no cancellation for small
// rectangles).
//
// In double precision. Φ(a0) is known to about an ulp of Δ, the angle the rows' extent subtends, and
// the column's share u.x Ω is measured against it, so the map's error grows as Ω shrinks; the column
// runs along the axis whose Δ is the smaller. The row's point is formed from differences of squares
// (t1 − t0, B − b0) without cancellation. Measured against long-double references (Van Oosterom &
// Strackee for the sub-rectangle below the sampled column against u.x Ω, u.x = i/64, and the row's
// fraction of its column against u.y) over 400,000 random rectangles (x 1e-5 to 1 from the plane and
// 1e-3 to 100 beside, edges 1e-8 to 10, turned, away from the origin), the worse relative error of the
// two is at most 1.1e-9 for Ω above 1e-7 sr, 1.4e-8 above 1e-9, 3.9e-8 above 1e-10; 1.3e-7 between
// 1e-11 and 1e-10, 8e-7 between 1e-12 and 1e-11, 4.9e-6 between 1e-13 and 1e-12. Below
// kMinSolidAngle = 1e-10 sr (a square 1e-5 rad across), where the error is still 25 times below the
// 1e-6 that sets SphericalTriangle's threshold, the rectangle is sampled uniformly by area with its
// exact solid-angle density d² / (A |cos θ_L|), uniform in solid angle to about its angular size. The
// fallback is unbiased (tested).
//
// Edges perpendicular to within |cos| ≤ kMaxEdgeCos = 1e-6 (float vertices of a turned rectangle are
// off by ~1e-8): the map samples the rectangle spanned by edgeU and edgeV's part perpendicular to it,
// and each point (s, t) of it goes to corner + s edgeU + t edgeV, a shear that keeps area, so every
// direction meets the parallelogram itself and pdfDirection is the exact density (d / d')³ / Ω, d' the
// distance to the point before the shear (1 / Ω for an exact rectangle). More sheared
// parallelograms are sampled as the two spherical triangles corner c1 c2 and corner c2 c3 (c1 =
// corner + edgeU, c2 = c1 + edgeV, c3 = corner + edgeV; SphericalTriangle, each by area below its own
// threshold), one chosen by u.x against its share of Ω and u.x rescaled within that share, so the
// map stays a bijection from the unit square; the density is then 1 / Ω as well.
#pragma once

#include "core/lights/spherical_triangle.h"
#include "core/math/vec.h"

namespace penumbra {

struct SphericalRectangle {
  // Solid angles below this (sr) are sampled by area; see the file comment.
  static constexpr double kMinSolidAngle = 1e-10;
  // Edges whose |cos| exceeds this are a parallelogram, sampled as two spherical triangles.
  static constexpr double kMaxEdgeCos = 1e-6;
  // pdfDirection's inside test: s, t in [−tol, 1 + tol] for the point corner + s edgeU + t edgeV.
  static constexpr double kEdgeTolerance = 1e-9;

  // Sets up the map for the rectangle corner + s edgeU + t edgeV, s, t in [0, 1], seen from x on
  // either side. False when it subtends no solid angle (x in its plane, degenerate, non-finite).
  // Solid angles below minSolidAngle are sampled by area (the tests measure the map below the default).
  bool init(const Vec3& corner, const Vec3& edgeU, const Vec3& edgeV, const Vec3& x,
            double minSolidAngle = kMinSolidAngle);

  // The unit direction for u in [0,1)², towards the rectangle (finite for every such u).
  DVec3 sampleDirection(Vec2 u) const;
  // The density of sampleDirection at a unit direction w that meets the rectangle, 0 when it misses:
  // 1 / Ω (times (d / d')³ for nearly perpendicular edges, see the file comment), or (by area)
  // d² / (area |cos θ_L|) at the point w meets.
  double pdfDirection(const DVec3& w) const;
  // The map's point (s, t) for u, the direction's point being corner + s edgeU + t edgeV; u.x moves s
  // (t when swapped). Only for the rectangle's own map (not by area, not sheared).
  glm::dvec2 rectanglePoint(Vec2 u) const;

  double solidAngle = 0;  // Ω of the rectangle the map samples (of the two triangles when sheared)
  bool byArea = false;
  bool sheared = false;  // two spherical triangles

  // ---- the map's data ----
  DVec3 toCorner;      // corner − x
  DVec3 eu, ev;        // the edges (double)
  DVec3 normal;        // the unit normal, eu × ev / area
  double area;         // |eu × ev|
  double z0;           // toCorner · normal (±h)
  DVec3 dualU, dualV;  // s = (p − corner) · dualU, t = (p − corner) · dualV for p in the plane
  DVec3 shear;         // ev's part along eu
  // The rectangle's frame: the column axis a (along eu, or along ev when swapped), the row axis b.
  double h;
  bool swapped = false;
  double a0, a1, b0, b1;
  double invA, invB;                         // 1 / (a1 − a0), 1 / (b1 − b0)
  double phi0;                               // Φ(a0)
  double oneMinusCosDelta, onePlusCosSigma;  // of the rows' angles θ0, θ1
  // Sheared: the halves corner c1 c2 and corner c2 c3, and the first one's share of Ω.
  SphericalTriangle halves[2];
  double firstShare;
};

}  // namespace penumbra
