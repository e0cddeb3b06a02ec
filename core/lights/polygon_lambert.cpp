#include "core/lights/polygon_lambert.h"

#include <cmath>

namespace penumbra {

double polygonLightIrradianceFactor(const glm::dvec3& x, const glm::dvec3& n,
                                    const std::vector<glm::dvec3>& vertices) {
  const std::size_t count = vertices.size();
  if (count < 3) return 0;
  glm::dvec3 windingNormal(0);  // Newell's normal: any planar polygon, convex or not
  for (std::size_t i = 0; i < count; ++i) windingNormal += glm::cross(vertices[i], vertices[(i + 1) % count]);
  if (!(glm::dot(x - vertices[0], windingNormal) > 0)) return 0;
  // Sutherland–Hodgman against n · (p − x) ≥ 0.
  std::vector<glm::dvec3> clipped;
  for (std::size_t i = 0; i < count; ++i) {
    const glm::dvec3 &a = vertices[i], &b = vertices[(i + 1) % count];
    const double ha = glm::dot(n, a - x), hb = glm::dot(n, b - x);
    if (ha >= 0) clipped.push_back(a);
    if ((ha >= 0) != (hb >= 0)) clipped.push_back(a + (b - a) * (ha / (ha - hb)));
  }
  // u_i × u_i+1 formed as (v_i − x) × (v_i+1 − v_i) / (|v_i − x| |v_i+1 − x|): for a small polygon far
  // away each term stays accurate to rounding, so their sum, far smaller than the terms, does too.
  double sum = 0;
  const glm::dvec3 unitN = glm::normalize(n);
  for (std::size_t i = 0; i < clipped.size(); ++i) {
    const glm::dvec3 &a = clipped[i], &b = clipped[(i + 1) % clipped.size()];
    const glm::dvec3 da = a - x, db = b - x;
    const double la = glm::length(da), lb = glm::length(db);
    const glm::dvec3 c = glm::cross(da, b - a) / (la * lb);
    const double s = glm::length(c);
    if (!(s > 0)) continue;
    sum += std::atan2(s, glm::dot(da, db) / (la * lb)) * glm::dot(unitN, c) / s;
  }
  return 0.5 * std::fabs(sum);
}

double polygonLightIrradianceFactor(const PolygonLight& light, const glm::dvec3& x, const glm::dvec3& n) {
  Vec3 v[4];
  light.vertices(v);
  std::vector<glm::dvec3> vertices(v, v + light.vertexCount());
  return polygonLightIrradianceFactor(x, n, vertices);
}

}  // namespace penumbra
