// The two ways `direct` and MIS estimate the area-light integral ∫ Le cos θ dω at a shading point,
// each written once and shared:
//   light sampling: draws towards the area lights (spheres, then polygons) by a light measure
//                   (light_technique.h, polygon_light_technique.h), each shadow-tested, contributing
//                   Le cos θ / pdf;
//   direction sampling: hemisphere directions (uniform or cosine-weighted), each traced to the first
//                   surface, contributing Le cos θ / pdf where that surface is the front of an area light.
// A weight per sample (1 for `direct`, the MIS weight for MIS) multiplies each contribution.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/integrators/light_technique.h"
#include "core/integrators/polygon_light_technique.h"
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

// `samples` light-sampling draws towards one light (one sampler request, stratified over its draws;
// drawn even when the light cannot be sampled), each adding Le · (cos θ / pdf) · weight(sample, cos θ)
// to E.
template <LightMeasure kMeasure, class Light, class Weight>
inline void addLightIrradiance(const Scene& scene, const Light& light, const ShadingPoint& sp,
                               Sampler& sampler, int samples, const Weight& weight, Color3& E) {
  const LightTechnique<kMeasure, Light> technique(light, sp);
  const float lightScale = lightScaleOf(light);
  for (int i = 0; i < samples; ++i) {
    const Vec2 u = sampler.next2D(uint32_t(i), uint32_t(samples));
    LightSample s;
    float cosTheta;
    if (!unoccludedLightSample(scene, light, lightScale, technique, sp, u, s, cosTheta)) continue;
    E += s.Le * (technique.cosOverPdf(s, cosTheta) * weight(s, cosTheta));
  }
}

// Light sampling of every area light: `samples` draws per light, the mean over the draws, summed over
// the lights.
template <LightMeasure kMeasure, class Weight>
Color3 everyLightIrradiance(const Scene& scene, const ShadingPoint& sp, Sampler& sampler, int samples,
                            const Weight& weight) {
  Color3 E(0.f);
  for (const SphereLight& light : scene.sphereLights)
    addLightIrradiance<kMeasure>(scene, light, sp, sampler, samples, weight, E);
  for (const PolygonLight& light : scene.polygonLights)
    addLightIrradiance<kMeasure>(scene, light, sp, sampler, samples, weight, E);
  return E * (1.f / float(samples));  // the reciprocal is off the critical path
}

// Direction sampling: `samples` hemisphere directions about the shading normal (one sampler request,
// stratified among themselves), each traced; one that reaches the front of an area light contributes
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
    if (!scene.geometry.intersect(sp.spawnRay(w, INFINITY), lightHit)) continue;
    const SurfaceMaterial& met = scene.materials[lightHit.objectId];
    if (met.sphereLight >= 0) {
      const SphereLight& light = scene.sphereLights[met.sphereLight];
      const Color3 Le = light.eval(lightHit.p, lightHit.ng, w);
      if (isBlack(Le)) continue;
      E += Le * (cosOverPdf * weight(light, lightHit, w, local.z));
    } else if (const PolygonLight* light = scene.polygonLightOf(met, lightHit.primId)) {
      const Color3 Le = light->eval(w);
      if (isBlack(Le)) continue;
      E += Le * (cosOverPdf * weight(*light, lightHit, w, local.z));
    }
  }
  return E * (1.f / float(samples));
}

}  // namespace penumbra
