// Warps onto the unit sphere: densities are with respect to solid angle and assume unit inputs.
#include <cmath>

#include "core/math/float_util.h"
#include "core/sampling/warp.h"
#include "core/sampling/warp_util.h"

namespace penumbra {

namespace {

// A cone around +z described without cancellation: 1 - cos(theta_max) and sin^2(theta_max).
struct Cone {
  float cosThetaMax;
  float oneMinusCos;  // 1 - cos(theta_max) in (0, 2]; 0 marks a degenerate (empty) cone
  float sin2;         // sin^2(theta_max)

  static Cone fromCos(float c) {
    if (!(c < 1.f)) return {1.f, 0.f, 0.f};  // also catches NaN
    c = std::max(c, -1.f);
    float omc = 1.f - c;
    return {c, omc, omc * (1.f + c)};
  }
  static Cone fromSin2(float s2) {
    if (!(s2 > 0.f)) return {1.f, 0.f, 0.f};  // also catches NaN
    s2 = std::min(s2, 1.f);
    float omc = oneMinusSqrtOneMinus(s2);  // s2 / (1 + cos): no cancellation
    return {1.f - omc, omc, s2};
  }

  // pdf = 1 / (2 pi (1 - cos(theta_max))) inside the cone, 0 outside (and 0 for a degenerate cone).
  float pdf(const Vec3& v) const { return oneMinusCos > 0.f && contains(v) ? kInv2Pi / oneMinusCos : 0.f; }

  bool contains(const Vec3& v) const {
    if (cosThetaMax >= 0.f) {  // at most a hemisphere: compare sin^2, which is precise for narrow cones
      float r2 = v.x * v.x + v.y * v.y;
      return v.z >= 0.f && r2 <= sin2 * (r2 + v.z * v.z) * (1.f + kSupportSlack);
    }
    return v.z >= cosThetaMax * (1.f + kSupportSlack);
  }

  // 1 - cos(theta) = u1 (1 - cos(theta_max)): uniform in solid angle over the cap.
  Vec3 sample(Vec2 u) const {
    if (!(oneMinusCos > 0.f)) return Vec3(0.f, 0.f, 1.f);
    return directionFromOneMinusCos(u.x * oneMinusCos, u.y);
  }

  Vec2 inverse(const Vec3& v) const {
    if (!(oneMinusCos > 0.f)) return Vec2(0.f);
    return Vec2(clampUnit(oneMinusCosTheta(v) / oneMinusCos), phiToUnit(v.y, v.x));
  }
};

}  // namespace

// ---- uniform sphere: z = 1 - 2 u1, phi = 2 pi u2; pdf = 1 / (4 pi) ------------------------------
Vec3 Warp::squareToUniformSphere(Vec2 sample) {
  return directionFromOneMinusCos(2.f * sample.x, sample.y);
}

float Warp::squareToUniformSpherePdf(const Vec3&) {
  return kInv4Pi;
}

Vec2 Warp::uniformSphereToSquare(const Vec3& v) {
  return Vec2(clampUnit(0.5f * oneMinusCosTheta(v)), phiToUnit(v.y, v.x));
}

// ---- uniform hemisphere (+z): z = 1 - u1, phi = 2 pi u2; pdf = 1 / (2 pi) for z >= 0, else 0 ---
Vec3 Warp::squareToUniformHemisphere(Vec2 sample) {
  return directionFromOneMinusCos(sample.x, sample.y);
}

float Warp::squareToUniformHemispherePdf(const Vec3& v) {
  return v.z >= 0.f ? kInv2Pi : 0.f;
}

Vec2 Warp::uniformHemisphereToSquare(const Vec3& v) {
  return Vec2(clampUnit(oneMinusCosTheta(v)), phiToUnit(v.y, v.x));
}

// ---- cosine hemisphere (Nusselt: concentric disk lifted to the hemisphere) -----------------------
// pdf = cos(theta) / pi = z / pi for z >= 0, else 0. The concentric disk never reaches the rim for
// canonical inputs, so every sample has z >= ~2^-11.5 > 0 and a positive density.
Vec3 Warp::squareToCosineHemisphere(Vec2 sample) {
  float rho;
  const Vec2 p = concentricPoint(sample, rho);
  // z = sqrt(1 - rho^2) from (1 - rho)(1 + rho): exact-ish at the rim, where x^2 + y^2 may round to 1.
  return Vec3(p.x, p.y, safeSqrt((1.f - rho) * (1.f + rho)));
}

float Warp::squareToCosineHemispherePdf(const Vec3& v) {
  return v.z >= 0.f ? v.z * kInvPi : 0.f;
}

Vec2 Warp::cosineHemisphereToSquare(const Vec3& v) {
  return concentricDiskToSquare(Vec2(v.x, v.y));
}

// ---- uniform cone around +z ---------------------------------------------------------------------
// 1 - cos(theta) = u1 (1 - cos(theta_max)), phi = 2 pi u2;
// pdf = 1 / (2 pi (1 - cos(theta_max))) inside the cone, 0 outside. cos(theta_max) in [-1, 1).
Vec3 Warp::squareToUniformCone(Vec2 sample, float cosThetaMax) {
  return Cone::fromCos(cosThetaMax).sample(sample);
}

float Warp::squareToUniformConePdf(const Vec3& v, float cosThetaMax) {
  return Cone::fromCos(cosThetaMax).pdf(v);
}

// Same cone from sin^2(theta_max) in (0, 1] (at most a hemisphere): 1 - cos(theta_max) is computed
// as sin^2 / (1 + cos), accurate down to sin^2 ~ 1e-38; pdf = (1 + cos) / (2 pi sin^2) inside.
Vec3 Warp::squareToUniformConeSin2(Vec2 sample, float sin2ThetaMax) {
  return Cone::fromSin2(sin2ThetaMax).sample(sample);
}

float Warp::squareToUniformConeSin2Pdf(const Vec3& v, float sin2ThetaMax) {
  return Cone::fromSin2(sin2ThetaMax).pdf(v);
}

Vec2 Warp::uniformConeToSquare(const Vec3& v, float cosThetaMax) {
  return Cone::fromCos(cosThetaMax).inverse(v);
}

// ---- Beckmann microfacet normals ----------------------------------------------------------------
// tan^2(theta) = -alpha^2 log(1 - u1), phi = 2 pi u2;
// pdf = D(m) cos(theta) = exp(-tan^2(theta) / alpha^2) / (pi alpha^2 cos^3(theta)) for z > 0, else 0.
Vec3 Warp::squareToBeckmann(Vec2 sample, float alpha) {
  float tan2 = -alpha * alpha * std::log1p(-sample.x);
  float cosTheta = 1.f / std::sqrt(1.f + tan2);
  float sinTheta = std::sqrt(tan2 / (1.f + tan2));
  const SinCos phi = sinCosTurns(sample.y);
  return Vec3(sinTheta * phi.cos, sinTheta * phi.sin, cosTheta);
}

float Warp::squareToBeckmannPdf(const Vec3& m, float alpha) {
  if (!(alpha > 0.f) || !(m.z > 0.f)) return 0.f;
  // Double precision: cos^3 of a grazing float direction does not underflow, so no 0/0.
  double z = m.z, a2 = static_cast<double>(alpha) * alpha;
  double tan2 = (static_cast<double>(m.x) * m.x + static_cast<double>(m.y) * m.y) / (z * z);
  return static_cast<float>(std::exp(-tan2 / a2) / (kPiD * a2 * z * z * z));
}

Vec2 Warp::beckmannToSquare(const Vec3& m, float alpha) {
  if (!(alpha > 0.f) || !(m.z > 0.f)) return Vec2(kOneMinusEpsilon, phiToUnit(m.y, m.x));
  float tan2 = (m.x * m.x + m.y * m.y) / (m.z * m.z);
  return Vec2(clampUnit(-std::expm1(-tan2 / (alpha * alpha))), phiToUnit(m.y, m.x));
}

}  // namespace penumbra
