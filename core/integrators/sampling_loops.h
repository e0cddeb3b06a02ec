// The two ways `direct` and MIS estimate the area-light integral ∫ Le cos θ dω at a shading point,
// each written once and shared:
//   light sampling: draws towards the sphere lights by a light measure (core/integrators/light_technique.h),
//                   each shadow-tested, contributing Le cos θ / pdf;
//   direction sampling: hemisphere directions (uniform or cosine-weighted), each traced to the first
//                   surface, contributing Le cos θ / pdf where that surface is a sphere light.
// A weight per sample (1 for `direct`, the MIS weight for MIS) multiplies each contribution.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/integrators/light_technique.h"
#include "core/integrators/shading_point.h"
#include "core/sampling/sampler.h"
#include "core/sampling/warp.h"

namespace penumbra {

// The weight of a plain estimator's samples.
struct UnitWeight {
  template <class... Args>
  constexpr float operator()(const Args&...) const {
    return 1.f;
  }
};

// One light-sampling draw `u` towards `light` (whose shadow rays start lightScale-relative offsets
// away): true, with the sample and its cos θ, when it lights sp (a positive density and radiance,
// above the surface, unoccluded).
template <LightMeasure kMeasure>
inline bool unoccludedLightSample(const Scene& scene, const SphereLight& light, float lightScale,
                                  const LightTechnique<kMeasure>& technique, const ShadingPoint& sp, Vec2 u,
                                  LightSample& s, float& cosTheta) {
  if (!technique.canSample()) return false;
  s = technique.sample(u);
  if (!(s.pdf > 0.f) || isBlack(s.Le)) return false;
  cosTheta = glm::dot(sp.ns, s.wi);
  if (!leavesSurface(sp, s.wi, cosTheta)) return false;
  // Every traced sample faces x (far-side area samples have Le = 0): the light cannot block it.
  return !scene.geometry.occluded(sp.spawnShadowRayAlong(s.wi, s.dist, lightScale), light.geometryIndex);
}

// The scale of a light's coordinates, which sets how far its shadow rays stop short of it.
inline float lightScaleOf(const SphereLight& light) {
  return maxAbsComponent(light.sphere.center) + light.sphere.radius;
}

// Light sampling of every sphere light: `samples` draws per light (one sampler request per light,
// stratified over its draws; drawn even for a light that cannot be sampled), each contributing
// Le · (cos θ / pdf) · weight(sample, cos θ); the mean over the draws, summed over the lights.
template <LightMeasure kMeasure, class Weight>
Color3 everyLightIrradiance(const Scene& scene, const ShadingPoint& sp, Sampler& sampler, int samples,
                            const Weight& weight) {
  Color3 E(0.f);
  for (const SphereLight& light : scene.sphereLights) {
    const LightTechnique<kMeasure> technique(light, sp);
    const float lightScale = lightScaleOf(light);
    for (int i = 0; i < samples; ++i) {
      const Vec2 u = sampler.next2D(uint32_t(i), uint32_t(samples));
      LightSample s;
      float cosTheta;
      if (!unoccludedLightSample(scene, light, lightScale, technique, sp, u, s, cosTheta)) continue;
      E += s.Le * (technique.cosOverPdf(s, cosTheta) * weight(s, cosTheta));
    }
  }
  return E * (1.f / float(samples));  // the reciprocal is off the critical path
}

// The sphere light that the ray from sp along w meets first, with the point met; null when the ray
// meets nothing or a surface that is not a light.
inline const SphereLight* lightAlong(const Scene& scene, const ShadingPoint& sp, const Vec3& w,
                                     SurfaceHit& lightHit) {
  if (!scene.geometry.intersect(sp.spawnRay(w, INFINITY), lightHit)) return nullptr;
  const int32_t light = scene.materials[lightHit.objectId].sphereLight;
  return light < 0 ? nullptr : &scene.sphereLights[light];
}

// Direction sampling: `samples` hemisphere directions about the shading normal (one sampler request,
// stratified among themselves), each traced; one that reaches a sphere light contributes
// Le · (cos θ / pdf) · weight(light, lightHit, w, cos θ), with cos θ / pdf in closed form (π for the
// cosine warp, 2π cos θ for the uniform one). Their mean.
template <HemisphereWarp kWarp, class Weight>
Color3 hemisphereIrradiance(const Scene& scene, const ShadingPoint& sp, Sampler& sampler, int samples,
                            const Weight& weight) {
  Color3 E(0.f);
  for (int i = 0; i < samples; ++i) {
    const Vec2 u = sampler.next2D(uint32_t(i), uint32_t(samples));
    Vec3 local;
    float cosOverPdf;
    if constexpr (kWarp == HemisphereWarp::Cosine) {
      local = Warp::squareToCosineHemisphere(u);
      if (!(local.z > 0.f)) continue;
      cosOverPdf = kPi;
    } else {
      local = Warp::squareToUniformHemisphere(u);
      cosOverPdf = 2.f * kPi * local.z;
    }
    const Vec3 w = sp.frame.toWorld(local);
    if (!leavesSurface(sp, w, local.z)) continue;
    SurfaceHit lightHit;
    const SphereLight* light = lightAlong(scene, sp, w, lightHit);
    if (!light) continue;
    const Color3 Le = light->eval(lightHit.p, lightHit.ng, w);
    if (isBlack(Le)) continue;
    E += Le * (cosOverPdf * weight(*light, lightHit, w, local.z));
  }
  return E * (1.f / float(samples));
}

}  // namespace penumbra
