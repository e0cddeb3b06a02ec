// How a shading point turns incident radiance into reflected radiance, the one thing the estimators
// need of its BSDF. Two kinds, chosen once per camera sample so that the sampling loops are compiled
// for each:
//   DiffuseReflection: f is albedo/π everywhere, so the loops estimate the irradiance ∫ Le cos θ dω and
//                      directRadiance applies albedo/π once (the diffuse code is what it was before
//                      glossy surfaces existed);
//   GlossyReflection:  f depends on both directions, so every sample carries f(wo, wi) and the loops
//                      estimate ∫ Le f cos θ dω directly.
// Both also give the density of the surface's own direction sampling (cosine hemisphere for diffuse,
// the BSDF's sampler otherwise), which multiple importance sampling weighs light samples against.
#pragma once

#include "core/integrators/shading_point.h"
#include "core/materials/bsdf.h"
#include "core/math/vec.h"

namespace penumbra {

struct DiffuseReflection {
  static constexpr bool kDiffuse = true;
  // The sample's factor beyond Le: 1 (albedo/π is applied to the whole estimate).
  const Color3& operator()(const Color3& Le, const Vec3& /*wi*/) const { return Le; }
  // The cosine-hemisphere density of wi, from its cosine to the shading normal.
  float pdf(const Vec3& /*wi*/, float cosTheta) const { return cosTheta * kInvPi; }
};

struct GlossyReflection {
  static constexpr bool kDiffuse = false;
  const Bsdf* bsdf;
  Frame frame;  // the shading point's
  Vec3 wo;      // towards the viewer, in the local frame

  GlossyReflection(const Bsdf& b, const ShadingPoint& sp, const Vec3& rayDirection)
      : bsdf(&b), frame(sp.frame), wo(sp.frame.toLocal(-rayDirection)) {}
  // From the frame and wo the constructor above computes (the packet kernels keep them per lane).
  GlossyReflection(const Bsdf& b, const Frame& f, const Vec3& woLocal) : bsdf(&b), frame(f), wo(woLocal) {}

  Color3 operator()(const Color3& Le, const Vec3& wi) const {
    return Le * evalBsdf(*bsdf, wo, frame.toLocal(wi));
  }
  float pdf(const Vec3& wi, float /*cosTheta*/) const { return pdfBsdf(*bsdf, wo, frame.toLocal(wi)); }
};

}  // namespace penumbra
