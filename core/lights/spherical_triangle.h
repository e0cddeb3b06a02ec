// Uniform solid-angle sampling of a triangle light: directions uniform over the spherical triangle
// the triangle subtends at a point x (Arvo, "Stratified Sampling of Spherical Triangles", SIGGRAPH
// 1995), density 1 / Ω with Ω by Van Oosterom & Strackee's formula (one atan2, accurate for small
// triangles). A bijection from the unit square: u.x chooses the sub-triangle A B Ĉ of area u.x Ω (Ĉ on
// the arc from A to C), u.y the point on the arc from B to Ĉ whose cos to B is interpolated linearly.
//
// In double precision. The map's terms are differences of numbers of the size of the triangle's angles
// whose result is of the size of Ω, so its error grows as Ω shrinks: the sub-triangle it chooses is
// off its area u.x Ω by 7e-11 at Ω = 4e-3, 1.3e-8 at 4e-5, 4.8e-7 at 4e-7 and 1e-4 at 4e-9 (measured by
// the tests). Below kMinSolidAngle = 1e-6 sr the triangle is sampled uniformly by area instead, with
// its exact solid-angle density (d² / (A |cos θ_L|)), which for so small a triangle (under 1e-3 rad
// across) is uniform in solid angle to about its angular size. The fallback is unbiased (tested).
#pragma once

#include "core/math/vec.h"

namespace penumbra {

struct SphericalTriangle {
  // Solid angles below this (sr) are sampled by area; see the file comment.
  static constexpr double kMinSolidAngle = 1e-6;

  // Sets up the map for the triangle v0 v1 v2 (either winding) seen from x. False when it subtends no
  // solid angle (x in its plane, degenerate, non-finite). Solid angles below minSolidAngle are sampled
  // by area (the tests measure the map below the default).
  bool init(const Vec3& v0, const Vec3& v1, const Vec3& v2, const Vec3& x,
            double minSolidAngle = kMinSolidAngle);

  // The unit direction for u in [0,1)², towards the triangle.
  DVec3 sampleDirection(Vec2 u) const;
  // The density of sampleDirection at a unit direction w that meets the triangle: 1 / Ω, or (by area,
  // below kMinSolidAngle) d² / (area |cos θ_L|) at the point w meets; 0 when w misses it.
  double pdfDirection(const DVec3& w) const;

  double solidAngle = 0;
  bool byArea = false;

  // ---- the map's data ----
  DVec3 origin;      // x
  DVec3 p0, e1, e2;  // the triangle: p0 + s e1 + t e2 (double)
  DVec3 a, b, c;     // unit directions to the vertices
  double alpha;      // the spherical triangle's angle at a
  double sinAlpha, cosAlpha;
  double cosC;           // a · b (the arc c opposite the vertex c)
  DVec3 cPerp;           // unit, perpendicular to a in the plane of a and c (towards c)
  DVec3 normal;          // the triangle's unit normal
  double area;           // the triangle's area
  DVec3 edgeNormals[3];  // inside the spherical triangle: w · n ≥ 0 for all three
};

}  // namespace penumbra
