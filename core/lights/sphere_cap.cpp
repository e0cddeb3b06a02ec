#include "core/lights/sphere_cap.h"

#include <algorithm>
#include <cmath>

#include "core/math/vec.h"

namespace penumbra {

namespace {

double sqrtNonNeg(double v) {
  return std::sqrt(std::max(v, 0.0));
}

// Straddling regime, stable form. Requires |cos θ| < sin α, sin α < 1.
double straddlingStable(double cosTheta, double sinTheta, double sinAlpha, double cosAlpha) {
  // y = -cot α cot θ; |y| < 1 in this regime (sin θ > cos α ≥ 0), clamp for rounding.
  const double y = std::clamp(-(cosAlpha * cosTheta) / (sinAlpha * sinTheta), -1.0, 1.0);
  const double q = sqrtNonNeg((1.0 - y) * (1.0 + y));
  const double w = (sinAlpha / cosAlpha) * sinTheta * q;
  return sinAlpha * sinAlpha * (cosTheta * std::acos(y) + w) + atanMinusIdentity(w);
}

double surfaceLimit(double cosTheta) {
  return 0.5 * kPiD * (1.0 + std::clamp(cosTheta, -1.0, 1.0));
}

}  // namespace

double atanMinusIdentity(double w) {
  if (std::abs(w) >= 0.1) return std::atan(w) - w;
  // atan w - w = Σ_{k≥1} (-1)^k w^{2k+1} / (2k+1); |w| < 0.1 makes each term ≤ 1e-2 of the previous.
  const double w2 = w * w;
  double power = w * w2, sum = 0.0;
  for (int k = 1; k <= 12; ++k) {
    const double term = power / (2 * k + 1);
    sum += (k % 2 == 1) ? -term : term;
    if (std::abs(term) <= 1e-18 * std::abs(sum)) break;
    power *= w2;
  }
  return sum;
}

double sphereLightHorizonFactor(double alpha) {
  if (alpha >= 0.5) return alpha - std::sin(alpha) * std::cos(alpha);
  // α - sin α cos α = (u - sin u)/2 with u = 2α; u - sin u = Σ_{k≥1} (-1)^{k+1} u^{2k+1}/(2k+1)!.
  const double u = 2.0 * alpha, u2 = u * u;
  double term = u * u2 / 6.0, sum = 0.0;
  for (int k = 1; k <= 20; ++k) {
    sum += (k % 2 == 1) ? term : -term;
    if (std::abs(term) <= 1e-18 * std::abs(sum)) break;
    term *= u2 / ((2.0 * k + 2.0) * (2.0 * k + 3.0));
  }
  return 0.5 * sum;
}

double sphereLightStraddlingDirect(double cosTheta, double sinTheta, double sinAlpha, double cosAlpha) {
  const double y = std::clamp(-(cosAlpha * cosTheta) / (sinAlpha * sinTheta), -1.0, 1.0);
  const double q = sqrtNonNeg((1.0 - y) * (1.0 + y));
  return sinAlpha * sinAlpha * cosTheta * std::acos(y) - cosAlpha * sinAlpha * sinTheta * q +
         std::atan((sinAlpha / cosAlpha) * sinTheta * q);
}

double sphereLightIrradianceFactor(double cosTheta, double sinTheta, double sinAlpha, double cosAlpha) {
  cosTheta = std::clamp(cosTheta, -1.0, 1.0);
  sinAlpha = std::clamp(sinAlpha, 0.0, 1.0);
  if (sinAlpha == 0.0) return 0.0;
  if (sinAlpha >= 1.0 || cosAlpha <= 0.0) return surfaceLimit(cosTheta);
  if (cosTheta >= sinAlpha) return kPiD * sinAlpha * sinAlpha * cosTheta;  // fully above
  if (cosTheta <= -sinAlpha) return 0.0;                                   // fully below
  return std::max(0.0, straddlingStable(cosTheta, sinTheta, sinAlpha, cosAlpha));
}

double sphereLightIrradianceFactor(double cosTheta, double sinAlpha) {
  cosTheta = std::clamp(cosTheta, -1.0, 1.0);
  sinAlpha = std::clamp(sinAlpha, 0.0, 1.0);
  const double sinTheta = sqrtNonNeg((1.0 - cosTheta) * (1.0 + cosTheta));
  const double cosAlpha = sqrtNonNeg((1.0 - sinAlpha) * (1.0 + sinAlpha));
  return sphereLightIrradianceFactor(cosTheta, sinTheta, sinAlpha, cosAlpha);
}

}  // namespace penumbra
