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
// cumulative area, then Newton's method with bisection inside the wedge), u.y places r² uniformly
// between r_inner² and r_outer².
//
// Inside a wedge from unit azimuth vector a₀ to a₁ the azimuth is parametrised by the chord,
// v(λ) = a₀ + λ (a₁ − a₀), λ in [0, 1] (monotone below π; wedges wider than 3π/4 are
// halved, so the chord keeps 0.38 from the origin and the azimuth along it its precision). An edge's point at
// azimuth v is along P(v) = (|m_z| v, g · v) (g the horizontal part of m, turned to the
// upper half circle), linear in v, so the area it sweeps from a₀ is
//     ½ |m_z| atan2(λ |m_z| σ, P(a₀) · P(v(λ))),   σ = a₀ × (a₁ − a₀),
// with derivative ½ σ m_z² / |P|², and no trigonometry for the azimuth itself. Newton starts
// from the root of a model (each edge's swept area as λ ↦ αλ / (1 + βλ), exact for a straight
// edge in the projection, with the edge's slope at 0 and area at 1; against the horizon,
// where the wedge's width vanishes at an end, refined on the cubic with the wedge's area and
// end slopes), evaluates the area once with atan2 and after that by the increments between
// iterates (the atan of a small ratio by its series). Plain data, built once per (shading
// point, polygon) and reused for every sample there; double precision throughout (the
// polygon's edge normals are formed from its edge vectors, so a polygon 1e-6 of its distance
// across keeps ~1e-10 relative accuracy).
#pragma once

#include "core/math/vec.h"

namespace penumbra {

struct ProjectedPolygon {
  // A quad clipped to the horizon has five vertices.
  static constexpr int kMaxInputVertices = 4;
  static constexpr int kMaxVertices = kMaxInputVertices + 1;
  // A wedge spans at most 3π/4 (wider ones are halved): one per edge or vertex interval, at most two each.
  static constexpr int kMaxWedges = 2 * kMaxVertices;
  // Stop rule of the azimuth's inversion in a wedge: |area below φ − target| ≤ kAreaTolerance · the
  // wedge's area (the sampled φ's CDF is then off by at most 1e-12 of the wedge: far below a float
  // u's quantisation, 2^-24), or the bracket down to a few ulps of the chord parameter's [0, 1]; at most
  // kMaxInversionSteps steps (each halves the bracket at worst, so the bound is never the reason to stop
  // in practice: 2^-64).
  static constexpr double kAreaTolerance = 1e-12;
  static constexpr int kMaxInversionSteps = 64;

  // Sets up the map for the polygon `vertices` (count 3 or 4, convex, planar, in either winding) seen
  // from x with unit shading normal n. False (and projectedSolidAngle = 0) when no part of it lies
  // above the horizon with a positive projected solid angle (x in its plane, behind the horizon,
  // degenerate). Which side of the polygon emits is the light's business, not the map's.
  bool init(const Vec3* vertices, int count, const Vec3& x, const Vec3& n);

  // Sutherland–Hodgman against the upper half space z ≥ 0 of the local frame: `points` (count of them,
  // in order) with the normal of the edge that starts at each, into `clipped` and `clippedNormals` (at
  // most count + 1 each). An edge's part above the horizon keeps its great circle's normal; from a point
  // where the polygon leaves the upper half space the edge runs along the horizon, normal (0, 0, 1).
  // Returns the clipped vertex count.
  static int clipToUpperHalfSpace(const DVec3* points, const DVec3* normals, int count, DVec3* clipped,
                                  DVec3* clippedNormals);

  // Where the zenith is outside the clipped polygon, the wedges between consecutive vertex azimuths:
  // the vertices ordered by `alpha` (any increasing function of their azimuth over less than a turn),
  // each wedge with the vertices it starts and ends at and the edge of each chain from the lowest
  // azimuth to the highest (A counter-clockwise, B clockwise) that bounds it there. Wedges of no width
  // are left out; writes at most vertexCount − 1 and returns how many.
  struct AzimuthInterval {
    int from, to, edgeA, edgeB;
  };
  static int azimuthIntervals(const double* alpha, int vertexCount, AzimuthInterval* out);

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
  // One boundary edge as a wedge uses it: k = |m_z| and g = ∓(m_x, m_y) of its great circle's unit
  // normal m (the sign that puts P(v) = (k v, g · v) on the upper half circle), P(a₀)² and
  // P(a₀) · P(a₁ − a₀) at the wedge's start, and the model of its swept area, αλ / (1 + βλ). An edge on
  // the horizon has k = 1, g = 0.
  struct Edge {
    double k, gx, gy;
    double p0, pd;
    double alpha, beta;
  };
  // A wedge between two consecutive vertex azimuths: from the unit azimuth vector (ax, ay) to
  // (ax + dx, ay + dy), σ = a × d; `outer` bounds it away from the origin, `inner` towards it (none
  // when the polygon covers the normal's direction).
  struct Wedge {
    double ax, ay, dx, dy, sigma;
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
};

}  // namespace penumbra
