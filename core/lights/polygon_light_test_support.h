// Polygon lights as the light-sampling tests see them: the configurations a floor point meets (above,
// straddling, grazing, tiny, sliver, huge, at three scales), an inside test of their own, and the
// polygon's own coordinates for χ² binning.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/math/vec.h"

namespace penumbra::test {

inline const Vec3 kUp(0.f, 0.f, 1.f);

// A polygon light seen from x (normal n).
struct Config {
  const char* name;
  std::vector<Vec3> vertices;
  Vec3 x{0.f}, n{0.f, 0.f, 1.f};
  bool solidAnglePdfDetectable = true;  // cos θ varies over it enough for 10⁶ samples to see
  // χ² bins on the polygon itself (its parallelogram's coordinates), else on the projection disk (for a
  // polygon so large that its density crowds into a small part of it).
  bool binOnThePolygon = true;
};

inline std::vector<Vec3> square(Vec3 centre, Vec3 u, Vec3 v) {
  return {centre - u - v, centre + u - v, centre + u + v, centre - u + v};
}

inline std::vector<Vec3> scaled(std::vector<Vec3> p, float s, Vec3 offset) {
  for (Vec3& q : p) q = q * s + offset;
  return p;
}

// Each the way a floor point sees a ceiling light, a wall, a window: above the horizon with the normal's
// direction inside or outside it, straddling, grazing, tiny, sliver, huge; and the same at 1e-3 and 1e3.
inline std::vector<Config> polygonConfigs() {
  const std::vector<Vec3> overhead = square(Vec3(0.1f, -0.05f, 1.f), Vec3(0.4f, 0, 0), Vec3(0, 0.3f, 0));
  std::vector<Config> c = {
      {"overheadQuad", overhead},
      {"offsetTriangle", {Vec3(0.8f, 0.2f, 1.f), Vec3(1.6f, 0.1f, 1.2f), Vec3(1.1f, 0.9f, 0.9f)}},
      {"triangleOverNormal", {Vec3(-0.5f, -0.4f, 0.7f), Vec3(0.6f, -0.3f, 0.9f), Vec3(0.f, 0.7f, 0.8f)}},
      {"straddlingWall", square(Vec3(1.f, 0.2f, 0.1f), Vec3(0, 0.5f, 0), Vec3(0, 0, 0.5f))},
      {"straddlingTiltedOverNormal",
       square(Vec3(0.2f, 0.1f, 0.3f), Vec3(2.f, 0.f, 0.6f), Vec3(0.f, 1.5f, -0.4f))},
      {"straddlingTriangle", {Vec3(0.5f, -0.5f, -0.3f), Vec3(0.7f, 0.6f, 0.4f), Vec3(1.2f, 0.f, 0.6f)}},
      {"grazingWindow", square(Vec3(3.f, 0.f, 0.0105f), Vec3(0, 1.f, 0), Vec3(0, 0, 0.0095f)), Vec3(0.f), kUp,
       false},
      {"lightCentreOnHorizon", square(Vec3(2.f, 0.f, 0.f), Vec3(0, 0.7f, 0), Vec3(0.3f, 0, 0.6f))},
      {"tiny1e-6",
       {Vec3(0.6f, 0.3f, 0.7f), Vec3(0.6f + 1e-6f, 0.3f, 0.7f), Vec3(0.6f, 0.3f + 1e-6f, 0.7f)},
       Vec3(0.f),
       kUp,
       false},
      {"tinyOverNormal1e-6", square(Vec3(0, 0, 1), Vec3(1e-6f, 0, 0), Vec3(0, 1e-6f, 0)), Vec3(0.f), kUp,
       false},
      {"sliver1e4", {Vec3(-1.f, 0.2f, 1.f), Vec3(1.f, 0.2f, 1.f), Vec3(0.f, 0.2002f, 1.f)}},
      // Binned on the disk, where 1 / cos θ (the solid-angle density) has no finite integral to compare with.
      {"hugeNearlyAHemisphere", square(Vec3(0, 0, 0.01f), Vec3(100.f, 0, 0), Vec3(0, 100.f, 0)), Vec3(0.f),
       kUp, false, false},
      {"tiltedNormal", overhead, Vec3(0.2f, 0.1f, 0.f), glm::normalize(Vec3(0.6f, -0.3f, 0.7f))},
  };
  // The same scenes at 1e-3 and 1e3, far from the origin.
  for (float s : {1e-3f, 1e3f}) {
    const Vec3 offset = Vec3(3.f, -2.f, 5.f) * s;
    c.push_back({s < 1 ? "overheadQuad1e-3" : "overheadQuad1e3", scaled(overhead, s, offset), offset});
    c.push_back({s < 1 ? "straddlingWall1e-3" : "straddlingWall1e3",
                 scaled(square(Vec3(1.f, 0.2f, 0.1f), Vec3(0, 0.5f, 0), Vec3(0, 0, 0.5f)), s, offset),
                 offset});
  }
  return c;
}

inline std::vector<glm::dvec3> toDouble(const std::vector<Vec3>& v) {
  return std::vector<glm::dvec3>(v.begin(), v.end());
}

// Whether the ray from x along w meets the polygon (convex, either winding): an inside test of its own,
// independent of the map's edge normals.
inline bool rayMeetsPolygon(const Config& c, const DVec3& w) {
  const DVec3 x(c.x), v0(c.vertices[0]);
  const DVec3 nl = glm::cross(DVec3(c.vertices[1]) - v0, DVec3(c.vertices[2]) - v0);
  const double denom = glm::dot(nl, w);
  if (denom == 0) return false;
  const double t = glm::dot(nl, v0 - x) / denom;
  if (!(t > 0)) return false;
  const DVec3 p = x + w * t;
  int positive = 0, negative = 0;
  const size_t k = c.vertices.size();
  for (size_t i = 0; i < k; ++i) {
    const DVec3 a(c.vertices[i]), b(c.vertices[(i + 1) % k]);
    const double s = glm::dot(glm::cross(b - a, p - a), nl);
    (s >= 0 ? positive : negative)++;
  }
  return positive == 0 || negative == 0;
}

// The polygon's own coordinates: p = v0 + s a + t b over the parallelogram of its first edges (a
// triangle is its half s + t ≤ 1), onto [0,1]², with the density of directions carried over to them.
struct PlaneBox {
  DVec3 x, v0, a, b, nl, n;
  double jacobian;
  bool triangle;

  explicit PlaneBox(const Config& c)
      : x(c.x),
        v0(c.vertices[0]),
        a(DVec3(c.vertices[1]) - v0),
        b(DVec3(c.vertices.back()) - v0),
        nl(glm::normalize(glm::cross(a, b))),
        n(glm::normalize(DVec3(c.n))),
        jacobian(glm::length(glm::cross(a, b))),
        triangle(c.vertices.size() == 3) {}
  Vec3 toSquare(const DVec3& w) const {
    const double t = glm::dot(nl, v0 - x) / glm::dot(nl, w);
    const DVec3 q = x + w * t - v0;
    // Solve q = s a + t b (q lies in the plane).
    const double aa = glm::dot(a, a), ab = glm::dot(a, b), bb = glm::dot(b, b), qa = glm::dot(q, a),
                 qb = glm::dot(q, b), det = aa * bb - ab * ab;
    const double s = (qa * bb - qb * ab) / det, u = (qb * aa - qa * ab) / det;
    return Vec3(float(std::clamp(s, 0.0, double(kOneMinusEpsilon))),
                float(std::clamp(u, 0.0, double(kOneMinusEpsilon))), 0.f);
  }
  // The direction towards the point at (s, t), and the factor from a direction density to one over
  // [0,1]²: |cos θ_L| |a × b| / d². False outside the polygon or below the horizon.
  bool fromSquare(double s, double t, DVec3& w, double& factor) const {
    if (triangle && s + t > 1) return false;
    const DVec3 d = v0 + a * s + b * t - x;
    const double d2 = glm::dot(d, d);
    w = d / std::sqrt(d2);
    if (!(glm::dot(w, n) > 0)) return false;
    factor = std::fabs(glm::dot(nl, w)) * jacobian / d2;
    return true;
  }
};

}  // namespace penumbra::test
