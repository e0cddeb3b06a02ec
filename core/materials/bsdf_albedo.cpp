#include "core/materials/bsdf_albedo.h"

#include <cmath>

#include "core/math/frame.h"

namespace penumbra {

double integrateAboutMirror(const Vec3& wo, double alpha, const std::function<double(const Vec3&)>& g) {
  constexpr int nx = 2400, nphi = 720;
  const DVec3 o(wo);
  double sum = 0;
  for (int i = 0; i < nx; ++i) {
    const double x = (i + 0.5) / nx, s = x / (1 - x), dsdx = 1 / ((1 - x) * (1 - x));
    const double theta = std::atan(alpha * s), dthetads = alpha / (1 + alpha * alpha * s * s);
    const double sinT = std::sin(theta), cosT = std::cos(theta);
    for (int j = 0; j < nphi; ++j) {
      const double phi = 2 * kPiD * (j + 0.5) / nphi;
      const DVec3 h(sinT * std::cos(phi), sinT * std::sin(phi), cosT);
      const double oh = glm::dot(o, h);
      const DVec3 wi = 2 * oh * h - o;
      if (!(wi.z > 0)) continue;
      sum += g(Vec3(glm::normalize(wi))) * 4 * std::fabs(oh) * sinT * dthetads * dsdx;
    }
  }
  return sum * (2 * kPiD / nphi) / nx;
}

namespace {

// The diffuse part of a microfacet BSDF, integrated in closed form: kd (albedo) and 1 - ks (mass).
bool hasDiffusePart(const Bsdf& b) {
  return b.type == BsdfType::Microfacet || b.type == BsdfType::Diffuse;
}

}  // namespace

double directionalAlbedo(const Bsdf& b, const Vec3& wo) {
  if (!(wo.z > 0.f)) return 0;
  const double diffuse = hasDiffusePart(b) ? double(b.albedo.x) : 0.0;
  if (b.type == BsdfType::Diffuse) return diffuse;
  const float kdOverPi = b.type == BsdfType::Microfacet ? b.albedo.x * kInvPi : 0.f;
  return diffuse + integrateAboutMirror(wo, b.alpha, [&](const Vec3& wi) {
           return double(evalBsdf(b, wo, wi).x - kdOverPi) * wi.z;
         });
}

double sampledMass(const Bsdf& b, const Vec3& wo) {
  if (!(wo.z > 0.f)) return 0;
  if (b.type == BsdfType::Diffuse) return 1;
  const double diffuse = b.type == BsdfType::Microfacet ? 1.0 - b.ks : 0.0;
  return diffuse + integrateAboutMirror(wo, b.alpha, [&](const Vec3& wi) {
           return double(pdfBsdf(b, wo, wi)) - diffuse * wi.z / kPiD;
         });
}

double coneReflectance(const Bsdf& bsdf, const Vec3& wo, const glm::dvec3& axis, double cosMax, int n) {
  DVec3 s, t;
  orthonormalBasis(axis, s, t);
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    // Uniform in cos (dω = d cos dφ): cells of equal solid angle.
    const double cosA = 1 - (i + 0.5) / n * (1 - cosMax), sinA = std::sqrt(1 - cosA * cosA);
    for (int j = 0; j < n; ++j) {
      const double phi = 2 * kPiD * (j + 0.5) / n;
      const DVec3 w = axis * cosA + (s * std::cos(phi) + t * std::sin(phi)) * sinA;
      if (w.z <= 0) continue;
      sum += double(evalBsdf(bsdf, wo, Vec3(w)).x) * w.z;
    }
  }
  return sum * (1 - cosMax) * 2 * kPiD / (double(n) * n);
}

}  // namespace penumbra
