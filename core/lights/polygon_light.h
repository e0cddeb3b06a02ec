// A uniform, one-sided emitting triangle or parallelogram: one triangle of an emitting mesh, a pair of
// its triangles that form a parallelogram, or a `rectangle` shape. It emits `radiance` on the side its
// counter-clockwise winding's normal points to, n = normalize(e1 × e2); seen from behind it is dark.
// Plain struct, no virtuals: which measure samples it is the light technique's choice
// (core/integrators/light_technique.h), the direction maps live in spherical_triangle.h,
// spherical_rectangle.h and projected_polygon.h.
#pragma once

#include <cstdint>

#include "core/geometry/bounds.h"
#include "core/lights/light_sample.h"

namespace penumbra {

struct PolygonLight {
  // The points p0 + s e1 + t e2 with s, t ≥ 0 and s + t ≤ 1 (a triangle) or s, t ≤ 1 (a parallelogram).
  Vec3 p0{0.f}, e1{0.f}, e2{0.f};
  Vec3 n{0.f, 0.f, 1.f};  // unit normal of the emitting side
  float area = 0.f;
  float scale = 0.f;  // the largest |coordinate| of its vertices: how far its shadow rays stop short
  bool parallelogram = false;
  Color3 radiance{0.f};
  // Never skipped by its own shadow rays: the rest of an emitting mesh may shadow a triangle of it.
  static constexpr int32_t geometryIndex = -1;

  // The light for a triangle or parallelogram; invalid (area 0) when it is degenerate or not finite.
  static PolygonLight make(const Vec3& p0, const Vec3& e1, const Vec3& e2, bool parallelogram,
                           const Color3& radiance);
  bool valid() const { return area > 0.f; }

  int vertexCount() const { return parallelogram ? 4 : 3; }
  // The vertices in counter-clockwise order about n.
  void vertices(Vec3 out[4]) const;
  Bounds bounds() const;
  Vec3 centroid() const;

  // Whether x is on the emitting side of the plane by more than the rounding of a point on it (2^-20 of
  // the coordinates' magnitude, the ray offsets' scale): only then can the light reach it. A point of
  // the light itself, or of a coplanar neighbour, is never lit by it.
  bool faces(const Vec3& x) const;

  // Uniform point on the polygon. sample.pdf is the SOLID-ANGLE density at x of the sampled
  // direction, d² / (area · |cos θp|); pdf = 0 when x does not face the light, when cos θp == 0
  // exactly, or when the density does not fit in a float (never +inf).
  LightSample sampleArea(const Vec3& x, Vec2 u) const;
  // Solid-angle density at x of sampleArea producing point p: d² / (area · |cos θp|) (0 when
  // cos θp == 0 or p == x).
  float pdfAreaAsSolidAngle(const Vec3& x, const Vec3& p) const;

  // The sample for a unit direction w from x (double) that meets the polygon: the point where it meets
  // the plane, its distance, Le = radiance; pdf is the caller's. Invalid (pdf left 0) when w does not
  // meet the plane in front of x.
  LightSample sampleAlong(const Vec3& x, const DVec3& w) const;

  // Radiance leaving the light toward a point that sees it along wi (from that point toward the
  // light): `radiance` on the emitting side (dot(n, −wi) > 0), else 0.
  Color3 eval(const Vec3& wi) const { return glm::dot(n, wi) < 0.f ? radiance : Color3(0.f); }
};

// Emitted power π · L · area (the mean of L's channels), 0 exactly when the light cannot contribute.
double polygonLightPower(const PolygonLight& light);

}  // namespace penumbra
