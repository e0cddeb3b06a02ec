// The two ways `direct` and MIS estimate the area-light integral ∫ Le f cos θ dω at a shading point,
// each written once and shared:
//   light sampling: draws towards the area lights (spheres, then polygons) by a light measure
//                   (light_technique.h, polygon_light_technique.h), each shadow-tested, contributing
//                   Le f cos θ / pdf;
//   direction sampling: hemisphere directions (uniform or cosine-weighted) or the BSDF's own
//                   directions, each traced to the first surface, contributing Le f cos θ / pdf where
//                   that surface is the front of an area light.
// f is the reflection's factor (reflection.h): 1 on a diffuse surface, whose estimate is then the
// irradiance. A weight per sample (1 for `direct`, the MIS weight for MIS) multiplies each
// contribution.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/integrators/direct_lighting.h"
#include "core/integrators/light_technique.h"
#include "core/integrators/polygon_light_technique.h"
#include "core/integrators/reflection.h"
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
template <LightMeasure kMeasure, class Light>
inline bool unoccludedLightSample(const Scene& scene, const Light& light, float lightScale,
                                  const LightTechnique<kMeasure, Light>& technique, const ShadingPoint& sp,
                                  Vec2 u, LightSample& s, float& cosTheta) {
  if (!technique.canSample()) return false;
  s = technique.sample(u);
  if (!(s.pdf > 0.f) || isBlack(s.Le)) return false;
  cosTheta = glm::dot(sp.ns, s.wi);
  if (!leavesSurface(sp, s.wi, cosTheta)) return false;
  // Every traced sample faces x (far-side area samples have Le = 0): a convex light cannot block it.
  return !scene.geometry.occluded(sp.spawnShadowRayAlong(s.wi, s.dist, lightScale), light.geometryIndex);
}

// The scale of a light's coordinates, which sets how far its shadow rays stop short of it.
inline float lightScaleOf(const SphereLight& light) {
  return maxAbsComponent(light.sphere.center) + light.sphere.radius;
}
inline float lightScaleOf(const PolygonLight& light) {
  return light.scale;
}

// One light-sampling draw u towards `light`: E += Le f · (cos θ / pdf) · weight(sample, cos θ) where it
// lights sp.
template <LightMeasure kMeasure, class Light, class Reflection, class Weight>
inline void addLightDraw(const Scene& scene, const Light& light, float lightScale,
                         const LightTechnique<kMeasure, Light>& technique, const ShadingPoint& sp,
                         const Reflection& reflection, Vec2 u, const Weight& weight, Color3& E) {
  LightSample s;
  float cosTheta;
  if (!unoccludedLightSample(scene, light, lightScale, technique, sp, u, s, cosTheta)) return;
  E += reflection(s.Le, s.wi) * (technique.cosOverPdf(s, cosTheta) * weight(s, cosTheta));
}

// One draw u towards a light picked with probability pmf: Le f cos θ / (pdf · pmf), 0 where it does not
// light sp.
template <LightMeasure kMeasure, class Light, class Reflection>
inline Color3 selectedLightSample(const Scene& scene, const Light& light, const ShadingPoint& sp,
                                  const Reflection& reflection, Vec2 u, double pmf) {
  const LightTechnique<kMeasure, Light> technique(light, sp);
  LightSample s;
  float cosTheta;
  if (!unoccludedLightSample(scene, light, lightScaleOf(light), technique, sp, u, s, cosTheta))
    return Color3(0.f);
  return reflection(s.Le, s.wi) * static_cast<float>(technique.cosOverSelectedPdf(s, cosTheta, pmf));
}

// `samples` light-sampling draws towards one light (one sampler request, stratified over its draws;
// drawn even when the light cannot be sampled), each adding Le f · (cos θ / pdf) · weight(sample, cos θ)
// to E.
template <LightMeasure kMeasure, class Light, class Reflection, class Weight>
inline void addLightIrradiance(const Scene& scene, const Light& light, const ShadingPoint& sp,
                               const Reflection& reflection, Sampler& sampler, int samples,
                               const Weight& weight, Color3& E) {
  const LightTechnique<kMeasure, Light> technique(light, sp);
  const float lightScale = lightScaleOf(light);
  for (int i = 0; i < samples; ++i)
    addLightDraw(scene, light, lightScale, technique, sp, reflection,
                 sampler.next2D(uint32_t(i), uint32_t(samples)), weight, E);
}

// Light sampling of every area light: `samples` draws per light, the mean over the draws, summed over
// the lights.
template <LightMeasure kMeasure, class Reflection, class Weight>
Color3 everyLightIrradiance(const Scene& scene, const ShadingPoint& sp, const Reflection& reflection,
                            Sampler& sampler, int samples, const Weight& weight) {
  Color3 E(0.f);
  for (const SphereLight& light : scene.sphereLights)
    addLightIrradiance<kMeasure>(scene, light, sp, reflection, sampler, samples, weight, E);
  for (const PolygonLight& light : scene.polygonLights)
    addLightIrradiance<kMeasure>(scene, light, sp, reflection, sampler, samples, weight, E);
  return E * (1.f / float(samples));  // the reciprocal is off the critical path
}

// What a traced direction w finds: when its first surface is the front of an area light,
// add(light, lightHit, Le) is called with that light (a SphereLight or PolygonLight), the hit and the
// radiance it sends back along w (not called when w finds no emitter facing sp).
template <class Add>
[[gnu::always_inline]] inline void addEmitterAlong(const Scene& scene, const ShadingPoint& sp, const Vec3& w,
                                                   const Add& add) {
  SurfaceHit lightHit;
  if (!scene.geometry.intersect(sp.spawnRay(w, INFINITY), lightHit)) return;
  const SurfaceMaterial& met = scene.materials[lightHit.objectId];
  if (met.sphereLight >= 0) {
    const SphereLight& light = scene.sphereLights[met.sphereLight];
    const Color3 Le = light.eval(lightHit.p, lightHit.ng, w);
    if (!isBlack(Le)) add(light, lightHit, Le);
  } else if (const PolygonLight* light = scene.polygonLightOf(met, lightHit.primId)) {
    const Color3 Le = light->eval(w);
    if (!isBlack(Le)) add(*light, lightHit, Le);
  }
}

// Direction sampling: `samples` hemisphere directions about the shading normal (one sampler request,
// stratified among themselves), each traced; one that reaches the front of an area light contributes
// Le f · (cos θ / pdf) · weight(light, lightHit, w, pdf), with cos θ / pdf in closed form (π for the
// cosine warp, 2π cos θ for the uniform one). Their mean.
template <HemisphereWarp kWarp, class Reflection, class Weight>
Color3 hemisphereIrradiance(const Scene& scene, const ShadingPoint& sp, const Reflection& reflection,
                            Sampler& sampler, int samples, const Weight& weight) {
  Color3 E(0.f);
  for (int i = 0; i < samples; ++i) {
    const Vec2 u = sampler.next2D(uint32_t(i), uint32_t(samples));
    Vec3 local;
    float cosOverPdf, pdf;
    if constexpr (kWarp == HemisphereWarp::Cosine) {
      local = Warp::squareToCosineHemisphere(u);
      if (!(local.z > 0.f)) continue;
      cosOverPdf = kPi;
      pdf = local.z * kInvPi;
    } else {
      local = Warp::squareToUniformHemisphere(u);
      cosOverPdf = 2.f * kPi * local.z;
      pdf = 0.5f * kInvPi;
    }
    const Vec3 w = sp.frame.toWorld(local);
    if (!leavesSurface(sp, w, local.z)) continue;
    addEmitterAlong(scene, sp, w, [&](const auto& light, const SurfaceHit& lightHit, const Color3& Le) {
      E += reflection(Le, w) * (cosOverPdf * weight(light, lightHit, w, pdf));
    });
  }
  return E * (1.f / float(samples));
}

// BSDF sampling on a glossy surface: `samples` directions drawn by the BSDF's own sampler (one
// sampler request), each traced; one that reaches the front of an area light contributes
// Le · (f cos θ / pdf) · weight(light, lightHit, w, pdf). Their mean. (On a diffuse surface the BSDF's
// sampler is the cosine warp: hemisphereIrradiance<Cosine>.)
template <class Weight>
Color3 bsdfSampledRadiance(const Scene& scene, const ShadingPoint& sp, const GlossyReflection& glossy,
                           Sampler& sampler, int samples, const Weight& weight) {
  Color3 E(0.f);
  for (int i = 0; i < samples; ++i) {
    const Vec2 u = sampler.next2D(uint32_t(i), uint32_t(samples));
    const BsdfSample s = sampleBsdf(*glossy.bsdf, glossy.wo, u);
    if (!(s.pdf > 0.f)) continue;
    const Vec3 w = sp.frame.toWorld(s.wi);
    if (!leavesSurface(sp, w, s.wi.z)) continue;
    addEmitterAlong(scene, sp, w, [&](const auto& light, const SurfaceHit& lightHit, const Color3& Le) {
      E += Le * s.weight * weight(light, lightHit, w, s.pdf);
    });
  }
  return E * (1.f / float(samples));
}

// Direction sampling by the surface's own sampler: cosine hemisphere on a diffuse surface, the BSDF's
// on a glossy one.
template <class Reflection, class Weight>
Color3 surfaceSampledRadiance(const Scene& scene, const ShadingPoint& sp, const Reflection& reflection,
                              Sampler& sampler, int samples, const Weight& weight) {
  if constexpr (Reflection::kDiffuse)
    return hemisphereIrradiance<HemisphereWarp::Cosine>(scene, sp, reflection, sampler, samples, weight);
  else
    return bsdfSampledRadiance(scene, sp, reflection, sampler, samples, weight);
}

}  // namespace penumbra
