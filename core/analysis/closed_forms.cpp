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
