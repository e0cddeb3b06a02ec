// The reflection models a surface can have, as plain data, and the three operations every estimator
// needs of them: evaluation, importance sampling and the density of that sampling. All directions are
// unit vectors in the local shading frame (normal +z); wo points towards the viewer, wi towards the
// light. f = 0 unless both are above the surface (z > 0).
//
// diffuse:          f = albedo / π; sampling: cosine hemisphere, pdf cos θi / π.
// microfacet:       the Nori family's model, f = kd/π + ks · D(h) F(h·wi) G1(wi,h) G1(wo,h) / (4 cosθi cosθo)
//                   with ks = 1 - max(kd), Beckmann D, Walter et al. 2007's rational G1 and the unpolarised
//                   dielectric Fresnel reflectance F between extIOR and intIOR
//                   (core/materials/microfacet_distribution.h).
// roughconductor:   Mitsuba 3's model, f = R · D(h) G1(wi,h) G1(wo,h) / (4 cosθi cosθo), Beckmann or GGX D
//                   (core/materials/microfacet_distribution.h); sampling: GGX by visible normals, Beckmann by
//                   all normals (bsdf.cpp says why).
#pragma once

#include <cstdint>

#include "core/math/vec.h"

namespace penumbra {

enum class BsdfType : uint8_t { Diffuse, Microfacet, RoughConductor };

// The roughness range of the microfacet models, where D, G1 and their sampling stay finite in float
// (scene files, `penumbra warp` and Python check it alike).
inline constexpr float kMinAlpha = 1e-6f, kMaxAlpha = 1e3f;
enum class MicrofacetDistribution : uint8_t { Beckmann, Ggx };

struct Bsdf {
  BsdfType type = BsdfType::Diffuse;
  Color3 albedo{0.5f};  // diffuse: albedo; microfacet: kd (the diffuse part); roughconductor: unused (0)
  float alpha = 0.1f;   // microfacet, roughconductor: the roughness
  MicrofacetDistribution distribution = MicrofacetDistribution::Beckmann;  // roughconductor
  float intIOR = 1.5046f, extIOR = 1.000277f;                              // microfacet
  Color3 specularReflectance{1.f};                                         // roughconductor: R
  float ks = 0.f;  // microfacet: 1 - max(kd), set by makeMicrofacet (also the specular lobe's probability)

  bool isDiffuse() const { return type == BsdfType::Diffuse; }
  // False when f = 0 everywhere (a black diffuse or conductor surface): nothing to estimate.
  bool reflects() const {
    if (type == BsdfType::RoughConductor) return !isBlack(specularReflectance);
    return !isBlack(albedo) || ks > 0.f;
  }
};

Bsdf makeDiffuse(const Color3& albedo);
Bsdf makeMicrofacet(const Color3& kd, float alpha, float intIOR, float extIOR);
Bsdf makeRoughConductor(MicrofacetDistribution distribution, float alpha, const Color3& specularReflectance);

// One sampled direction: wi, the estimator's factor f(wo, wi) cos θi / pdf (0 when the sample is
// rejected: wi below the surface, or a zero density), and the solid-angle density pdf.
struct BsdfSample {
  Vec3 wi{0.f};
  Color3 weight{0.f};
  float pdf = 0.f;
};

// f(wo, wi), per colour channel; never NaN, Inf or negative.
Color3 evalBsdf(const Bsdf& bsdf, const Vec3& wo, const Vec3& wi);
// A direction wi drawn from u in [0,1)² with density pdfBsdf(bsdf, wo, wi) (lobes chosen by reusing u.x).
BsdfSample sampleBsdf(const Bsdf& bsdf, const Vec3& wo, Vec2 u);
// The solid-angle density with which sampleBsdf produces wi from wo (0 below the surface).
float pdfBsdf(const Bsdf& bsdf, const Vec3& wo, const Vec3& wi);

}  // namespace penumbra
