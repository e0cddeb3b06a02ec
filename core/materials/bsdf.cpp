#include "core/materials/bsdf.h"

#include <algorithm>
#include <cmath>

#include "core/materials/fresnel.h"
#include "core/materials/microfacet_distribution.h"
#include "core/math/float_util.h"
#include "core/sampling/warp.h"

namespace penumbra {

namespace {

// The half vector of two directions above the surface (never zero: both have z > 0).
Vec3 halfVector(const Vec3& wo, const Vec3& wi) {
  return glm::normalize(wo + wi);
}

MicrofacetDistribution distributionOf(const Bsdf& b) {
  return b.type == BsdfType::Microfacet ? MicrofacetDistribution::Beckmann : b.distribution;
}

// The half vector of a direction pair and its D(h): what f and its density both need, computed once
// when a sample needs both.
struct HalfVectorTerms {
  Vec3 h;
  float D;
};
HalfVectorTerms halfVectorTerms(const Bsdf& b, const Vec3& wo, const Vec3& wi) {
  const Vec3 h = halfVector(wo, wi);
  return {h, microfacetD(distributionOf(b), h, b.alpha)};
}
// Whether f or its density has a specular lobe (needs HalfVectorTerms).
bool hasSpecularLobe(const Bsdf& b) {
  return b.type == BsdfType::RoughConductor || (b.type == BsdfType::Microfacet && b.ks > 0.f);
}

// D(h) G1(wi,h) G1(wo,h) / (4 cos θi cos θo): the specular term both microfacet models share.
float microfacetSpecular(MicrofacetDistribution dist, float alpha, const Vec3& wo, const Vec3& wi,
                         const HalfVectorTerms& t) {
  const Vec3& h = t.h;
  const float D = t.D;
  if (D == 0.f) return 0.f;
  const float G = microfacetG1(dist, wi, h, alpha) * microfacetG1(dist, wo, h, alpha);
  return D * G / (4.f * wi.z * wo.z);
}

// The density of wi = wo reflected about a normal h drawn with density pdfH (per solid angle of h):
// the reflection's Jacobian dωh/dωi = 1 / (4 |wi·h|).
float reflectedPdf(float pdfH, const Vec3& wi, const Vec3& h) {
  const float c = std::fabs(glm::dot(wi, h));
  return c > 0.f ? pdfH / (4.f * c) : 0.f;
}

// The density of the specular lobe's sampling of h seen from wo: all normals, D(h) cos θh (Beckmann),
// or GGX's visible normals, G1(wo,h) max(0, wo·h) D(h) / cos θo.
float normalPdf(MicrofacetDistribution dist, bool visible, float alpha, const Vec3& wo,
                const HalfVectorTerms& t) {
  const Vec3& h = t.h;
  const float D = t.D;
  if (!visible) return D * h.z;
  return microfacetG1(dist, wo, h, alpha) * std::fmax(0.f, glm::dot(wo, h)) * D / wo.z;
}

// The roughconductor samples GGX by visible normals, Beckmann by all normals (its G1 is Walter's fit,
// not the Smith term visible-normal sampling of Beckmann would need).
bool samplesVisibleNormals(const Bsdf& b) {
  return b.type == BsdfType::RoughConductor && b.distribution == MicrofacetDistribution::Ggx;
}

Vec3 sampleNormal(const Bsdf& b, const Vec3& wo, Vec2 u) {
  if (samplesVisibleNormals(b)) return sampleGgxVisibleNormal(wo, b.alpha, u);
  return Warp::squareToBeckmann(u, b.alpha);
}

// The density of wi through the specular lobe (its normal density reflected).
float specularPdf(const Bsdf& b, const Vec3& wo, const Vec3& wi, const HalfVectorTerms& t) {
  return reflectedPdf(normalPdf(distributionOf(b), samplesVisibleNormals(b), b.alpha, wo, t), wi, t.h);
}

// f and its density for directions above the surface; `t` is halfVectorTerms(b, wo, wi) when
// hasSpecularLobe(b) (unread otherwise).
Color3 evalAbove(const Bsdf& b, const Vec3& wo, const Vec3& wi, const HalfVectorTerms& t) {
  switch (b.type) {
    case BsdfType::Diffuse:
      return b.albedo * kInvPi;
    case BsdfType::Microfacet: {
      Color3 f = b.albedo * kInvPi;
      if (b.ks > 0.f) {
        const float spec = microfacetSpecular(MicrofacetDistribution::Beckmann, b.alpha, wo, wi, t);
        if (spec > 0.f) f += Color3(b.ks * spec * fresnelDielectric(glm::dot(t.h, wi), b.extIOR, b.intIOR));
      }
      return f;
    }
    case BsdfType::RoughConductor:
      return b.specularReflectance * microfacetSpecular(b.distribution, b.alpha, wo, wi, t);
  }
  return Color3(0.f);
}

float pdfAbove(const Bsdf& b, const Vec3& wo, const Vec3& wi, const HalfVectorTerms& t) {
  switch (b.type) {
    case BsdfType::Diffuse:
      return wi.z * kInvPi;
    case BsdfType::Microfacet: {
      float pdf = (1.f - b.ks) * wi.z * kInvPi;
      if (b.ks > 0.f) pdf += b.ks * specularPdf(b, wo, wi, t);
      return pdf;
    }
    case BsdfType::RoughConductor:
      return specularPdf(b, wo, wi, t);
  }
  return 0.f;
}

HalfVectorTerms termsIfNeeded(const Bsdf& b, const Vec3& wo, const Vec3& wi) {
  return hasSpecularLobe(b) ? halfVectorTerms(b, wo, wi) : HalfVectorTerms{Vec3(0.f, 0.f, 1.f), 0.f};
}

}  // namespace

Bsdf makeDiffuse(const Color3& albedo) {
  Bsdf b;
  b.albedo = albedo;
  return b;
}

Bsdf makeMicrofacet(const Color3& kd, float alpha, float intIOR, float extIOR) {
  Bsdf b;
  b.type = BsdfType::Microfacet;
  b.albedo = kd;
  b.alpha = alpha;
  b.intIOR = intIOR;
  b.extIOR = extIOR;
  b.ks = 1.f - maxComponent(kd);
  return b;
}

Bsdf makeRoughConductor(MicrofacetDistribution distribution, float alpha, const Color3& specularReflectance) {
  Bsdf b;
  b.type = BsdfType::RoughConductor;
  b.albedo = Color3(0.f);
  b.alpha = alpha;
  b.distribution = distribution;
  b.specularReflectance = specularReflectance;
  return b;
}

Color3 evalBsdf(const Bsdf& b, const Vec3& wo, const Vec3& wi) {
  if (!(wo.z > 0.f) || !(wi.z > 0.f)) return Color3(0.f);
  return evalAbove(b, wo, wi, termsIfNeeded(b, wo, wi));
}

float pdfBsdf(const Bsdf& b, const Vec3& wo, const Vec3& wi) {
  if (!(wo.z > 0.f) || !(wi.z > 0.f)) return 0.f;
  return pdfAbove(b, wo, wi, termsIfNeeded(b, wo, wi));
}

BsdfSample sampleBsdf(const Bsdf& b, const Vec3& wo, Vec2 u) {
  BsdfSample s;
  if (!(wo.z > 0.f)) return s;
  bool specular = b.type == BsdfType::RoughConductor;
  if (b.type == BsdfType::Microfacet) {
    // The lobe by u.x, which is then rescaled to [0,1) for the lobe's own warp.
    specular = u.x < b.ks;
    u.x = specular ? u.x / b.ks : (u.x - b.ks) / (1.f - b.ks);
    u.x = std::min(u.x, kOneMinusEpsilon);
  }
  s.wi = specular ? reflectAbout(wo, sampleNormal(b, wo, u)) : Warp::squareToCosineHemisphere(u);
  if (!(s.wi.z > 0.f)) return BsdfSample{};
  const HalfVectorTerms t = termsIfNeeded(b, wo, s.wi);  // shared by the density and f
  s.pdf = pdfAbove(b, wo, s.wi, t);
  if (!(s.pdf > 0.f) || !(s.pdf < INFINITY)) return BsdfSample{};
  s.weight = evalAbove(b, wo, s.wi, t) * (s.wi.z / s.pdf);
  if (!isValidRadiance(s.weight)) return BsdfSample{};
  return s;
}

}  // namespace penumbra
