#include "core/analysis/closed_forms.h"

#include <glm/gtx/component_wise.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/math/vec.h"

namespace penumbra {

double sphereLightIrradianceFactor(const glm::dvec3& x, const glm::dvec3& n, const glm::dvec3& c, double r,
                                   bool twoSided) {
  const double insideValue = twoSided ? kPiD : 0.0;
  const glm::dvec3 v = c - x;
  const double d = glm::length(v);
  const double nLen = glm::length(n);
  if (!(r > 0.0) || !(nLen > 0.0)) return 0.0;
  if (d == 0.0) return insideValue;
  // cos θ and sin θ from the geometry (sin θ via the cross product: accurate near θ = 0 and π).
  const double cosTheta = std::clamp(glm::dot(n, v) / (nLen * d), -1.0, 1.0);
  const double sinTheta = std::min(1.0, glm::length(glm::cross(n, v)) / (nLen * d));
  // On the surface up to the rounding of x, c and d (a few ulps of the coordinates); anything further
  // out uses the exact formulas, which converge to the surface limit like O(cos α) = O(√((d - r)/r)).
  const double coordScale = r + glm::compMax(glm::abs(x)) + glm::compMax(glm::abs(c));
  if (std::abs(d - r) <= 16 * std::numeric_limits<double>::epsilon() * coordScale)
    return sphereLightIrradianceFactor(cosTheta, sinTheta, 1.0, 0.0);  // the surface limit
  if (d < r) return insideValue;
  const double sinAlpha = r / d;
  const double cosAlpha = std::sqrt(((d - r) / d) * ((d + r) / d));
  return sphereLightIrradianceFactor(cosTheta, sinTheta, sinAlpha, cosAlpha);
}

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

double aoPlaneWithSphere(double cosTheta, double sinAlpha) {
  return 1.0 - sphereLightIrradianceFactor(cosTheta, sinAlpha) / kPiD;
}

double aoPlaneWithSphere(const glm::dvec3& x, const glm::dvec3& n, const glm::dvec3& c, double r) {
  // Inside the occluder every ray is blocked: the two-sided value π gives AO = 0.
  return 1.0 - sphereLightIrradianceFactor(x, n, c, r, /*twoSided=*/true) / kPiD;
}

double aoPlaneNearRestingSphere(double rho, double R) {
  const double t = (rho / R) * (rho / R);
  if (rho < R) return -std::expm1(-1.5 * std::log1p(t));
  return 1.0 - std::pow(1.0 + t, -1.5);  // = 1 - R³/(ρ² + R²)^{3/2}, overflow-free
}

double aoOnRestingConvexBody(double psi) {
  const double h = std::cos(0.5 * psi);
  return h * h;
}

}  // namespace penumbra
