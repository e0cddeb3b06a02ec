// Projected-solid-angle sampling of a convex planar polygon light (a triangle or a parallelogram):
// directions towards the polygon distributed in proportion to cos θ over the part of it above the
// shading point's horizon, with density cos θ / Ω⊥ (Ω⊥ that part's projected solid angle, Lambert's
// closed form). For an unoccluded diffuse receiver every sample's estimate Le cos θ / pdf is Le Ω⊥:
// zero variance. Peters (ACM TOG 40(4), 2021) samples the same density on the GPU; this map is
// derived here in polar coordinates on the projection disk and is exact in the same sense.
//
// Nusselt: a direction (x, y, z) about the normal projects to (x, y) on the unit disk, and
// cos θ dω = dx dy, so points uniform in the polygon's projection, lifted by z = √(1 − x² − y²), are
// cos-distributed. Clipped to the horizon (Sutherland–Hodgman), each edge of the polygon lies on a
// great circle with unit normal m; at azimuth φ that circle's point projects to radius
//     r²(φ) = m_z² / (m_z² + (1 − m_z²) cos² ψ),   ψ = φ − φ_m,
// an ellipse about the origin (semi-axes 1 and |m_z|; an edge on the horizon has r = 1), and the
// area it sweeps from ψ₀ to ψ₁ is ½ |m_z| (atan(|m_z| tan ψ₁) − atan(|m_z| tan ψ₀)), evaluated as one
// atan2 (no cancellation for short edges). A meridian (constant φ) meets the convex spherical polygon
// in one arc, so the projection is {φ in its azimuth range, r_inner(φ) ≤ r ≤ r_outer(φ)}, with
// r_inner = 0 when the polygon covers the normal's direction. Between consecutive vertex azimuths
// (a wedge) the inner and outer boundaries are single edges.
//
// The map of the unit square onto the region is a bijection that keeps stratification (no
// rejection): u.x picks φ by inverting the region's area at azimuths below φ (the wedge by its
// cumulative area, then Newton's method with bisection inside the wedge: the area's derivative is
// ½ (r_outer² − r_inner²), in closed form), u.y places r² uniformly between r_inner² and r_outer².
// Plain data, built once per (shading point, polygon) and reused for every sample there; double
// precision throughout (the polygon's edge normals are formed from its edge vectors, so a polygon
// 1e-6 of its distance across keeps ~1e-10 relative accuracy).
#pragma once

#include "core/math/vec.h"

namespace penumbra {

struct ProjectedPolygon {
  // A quad clipped to the horizon has five vertices.
  static constexpr int kMaxInputVertices = 4;
  static constexpr int kMaxVertices = kMaxInputVertices + 1;
  // A wedge spans at most π/2 (wider ones are halved): one per edge or vertex interval, at most two each.
  static constexpr int kMaxWedges = 2 * kMaxVertices;
  // Stop rule of the azimuth's inversion in a wedge: |area below φ − target| ≤ kAreaTolerance · the
  // wedge's area (the sampled φ's CDF is then off by at most 1e-12 of the wedge: far below a float
  // u's quantisation, 2^-24), or the bracket down to a few ulps of the wedge's span; at most
  // kMaxInversionSteps steps (each halves the bracket at worst, so the bound is never the reason to stop
  // in practice: 2^-64 of a span below π).
  static constexpr double kAreaTolerance = 1e-12;
  static constexpr int kMaxInversionSteps = 64;

  // Sets up the map for the polygon `vertices` (count 3 or 4, convex, planar, in either winding) seen
  // from x with unit shading normal n. False (and projectedSolidAngle = 0) when no part of it lies
  // above the horizon with a positive projected solid angle (x in its plane, behind the horizon,
  // degenerate). Which side of the polygon emits is the light's business, not the map's.
  bool init(const Vec3* vertices, int count, const Vec3& x, const Vec3& n);

  // The unit direction for u in [0,1)², in world coordinates, density pdfDirection.
  DVec3 sampleDirection(Vec2 u) const;
  // cos θ / Ω⊥ for a unit direction w inside the clipped polygon's cone above the horizon, else 0.
  double pdfDirection(const DVec3& w) const;

  // Ω⊥ of the clipped polygon, as the wedges integrate it (the map's own normaliser; equal to
  // Lambert's closed form to rounding).
  double projectedSolidAngle = 0;

  // ---- the map's data (read by the tests) ----
  // Local frame: ez the shading normal.
  DVec3 ex, ey, ez;
  // One boundary edge as the wedges use it: |m_z| and 1 − m_z² of its great circle's unit normal m,
  // and the unit azimuth vector (qx, qy) of ψ = 0, the circle's highest point (r = |m_z|; r = 1 at
  // ψ = ±π/2, where it meets the horizon). An edge on the horizon has k = 1, c2 = 0.
  struct Edge {
    double k, c2;
    double qx, qy;
  };
  // A wedge between two consecutive vertex azimuths: from the unit azimuth vector (ux, uy), `span`
  // radians counter-clockwise; `outer` bounds it away from the origin, `inner` towards it (none when
  // the polygon covers the normal's direction).
  struct Wedge {
    double ux, uy, span;
    Edge outer, inner;
    bool hasInner;
    double area;
  };
  Wedge wedges[kMaxWedges];
  int wedgeCount = 0;
  double cumulativeArea[kMaxWedges + 1];
  // The clipped polygon's edge normals in the local frame (inside: m · w ≥ 0 for every edge).
  DVec3 edgeNormals[kMaxVertices];
  int edgeCount = 0;

  // The area of wedge `w` at azimuths up to the unit azimuth vector (ux, uy), `t` radians past its
  // start (sinT = sin t).
  static double wedgeAreaTo(const Wedge& w, double ux, double uy, double sinT, double t);
};

}  // namespace penumbra
