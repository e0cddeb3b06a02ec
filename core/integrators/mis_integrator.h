// Direct illumination by multiple importance sampling (Veach's thesis, ch. 9, the multi-sample
// model): the area-light integral ∫ Le cos θ dω is estimated with two techniques at once,
//   light sampling: for every sphere light, `lightSamples` directions of the light measure
//                   (area, solid angle or projected solid angle), and
//   cosine-hemisphere sampling: `bsdfSamples` directions shared by all lights, a direction that
//                   reaches a light unoccluded counting for that light,
// each sample weighted by the balance or power (β = 2) heuristic of the two techniques' solid-angle
// densities there: F = Σ_t (1/n_t) Σ_j w_t(ω_tj) f(ω_tj) / p_t(ω_tj), with w_L + w_B = 1 for every
// direction both can produce. A count of 0 turns the other technique into the plain estimator
// (bit for bit: its weights are then exactly 1). Point and directional lights are deterministic.
//
// Several sphere lights: every light is sampled (the loop of `lightSelection` `all`), none is chosen
// by a light selection, so the mis rows take no `lightSelection`. The weight of a cosine direction
// that reaches light L needs the density with which light sampling would have produced it: L's
// selection probability times the technique's pdf. With the loop that probability is 1, the weights
// are per light (a hemisphere direction reaches one light, the nearest) and no selection pmf has to
// be evaluated at every hemisphere hit; selecting one light per sample pays off only for many lights.
#pragma once

#include <cmath>

#include "core/integrators/direct_lighting.h"
#include "core/integrators/light_technique.h"
#include "core/integrators/mis_weight.h"
#include "core/integrators/shading_point.h"
#include "core/sampling/sampler.h"
#include "core/sampling/warp.h"

namespace penumbra {

template <LightMeasure kMeasure, MisHeuristic kHeuristic>
struct MisIntegrator {
  int lightSamples = 1;  // per sphere light, per camera sample
  int bsdfSamples = 1;   // cosine-hemisphere directions per camera sample

  Color3 Li(const Scene& scene, const Ray& ray, Sampler& sampler) const {
    SurfaceHit hit;
    if (!scene.geometry.intersect(ray, hit)) return Color3(0.f);
    const SurfaceMaterial& material = scene.materials[hit.objectId];
    const Color3 L = emittedAt(scene, material, hit, ray);
    if (isBlack(material.albedo)) return L;

    ShadingPoint sp(scene, ray, hit);
    Color3 E = deltaIrradiance(scene, sp);
    if (scene.hasAreaLights()) {
      Color3 lightPart, bsdfPart;
      techniques(scene, sp, sampler, lightPart, bsdfPart);
      E += lightPart + bsdfPart;
    }
    return L + material.albedo * kInvPi * E;
  }

  // The two techniques' weighted irradiance estimates at a shading point (their sum is the estimate;
  // each alone is what the technique contributes to it).
  void techniques(const Scene& scene, const ShadingPoint& sp, Sampler& sampler, Color3& lightPart,
                  Color3& bsdfPart) const {
    lightPart = lightSamples > 0 ? lightTechnique(scene, sp, sampler) : Color3(0.f);
    bsdfPart = bsdfSamples > 0 ? bsdfTechnique(scene, sp, sampler) : Color3(0.f);
  }

  // The density of the cosine-hemisphere technique, and of the light technique for light `l`, of a
  // direction w reaching that light at p (normal n): the pair every weight is computed from.
  static float bsdfPdf(float cosTheta) { return cosTheta * kInvPi; }
  static float lightPdf(const SphereLight& l, const ShadingPoint& sp, const Vec3& w, const Vec3& p,
                        const Vec3& n) {
    return LightTechnique<kMeasure>(l, sp).pdf(w, p, n);
  }

 private:
  Color3 lightTechnique(const Scene& scene, const ShadingPoint& sp, Sampler& sampler) const {
    const float nL = float(lightSamples), nB = float(bsdfSamples);
    Color3 E(0.f);
    for (const SphereLight& light : scene.sphereLights) {
      const LightTechnique<kMeasure> technique(light, sp);
      const float lightScale = maxAbsComponent(light.sphere.center) + light.sphere.radius;
      for (int i = 0; i < lightSamples; ++i) {
        // One request per light, stratified over its lightSamples; drawn before canSample().
        Vec2 u = sampler.next2D(uint32_t(i), uint32_t(lightSamples));
        if (!technique.canSample()) continue;
        LightSample s = technique.sample(u);
        if (!(s.pdf > 0.f) || isBlack(s.Le)) continue;
        float cosTheta = glm::dot(sp.ns, s.wi);
        if (!leavesSurface(sp, s.wi, cosTheta)) continue;
        if (scene.geometry.occluded(sp.spawnShadowRayAlong(s.wi, s.dist, lightScale), light.geometryIndex))
          continue;
        const float weight = misWeight<kHeuristic>(nL * s.pdf, nB * bsdfPdf(cosTheta));
        E += s.Le * (technique.cosOverPdf(s, cosTheta) * weight);
      }
    }
    return E * (1.f / nL);
  }

  Color3 bsdfTechnique(const Scene& scene, const ShadingPoint& sp, Sampler& sampler) const {
    const float nL = float(lightSamples), nB = float(bsdfSamples);
    Color3 E(0.f);
    for (int i = 0; i < bsdfSamples; ++i) {
      Vec2 u = sampler.next2D(uint32_t(i), uint32_t(bsdfSamples));  // one request after the lights'
      Vec3 local = Warp::squareToCosineHemisphere(u);
      if (!(local.z > 0.f)) continue;
      Vec3 w = sp.frame.toWorld(local);
      if (!leavesSurface(sp, w, local.z)) continue;
      SurfaceHit lightHit;
      if (!scene.geometry.intersect(sp.spawnRay(w, INFINITY), lightHit)) continue;
      int32_t light = scene.materials[lightHit.objectId].sphereLight;
      if (light < 0) continue;
      const SphereLight& l = scene.sphereLights[light];
      const Color3 Le = l.eval(lightHit.p, lightHit.ng, w);
      if (isBlack(Le)) continue;
      const float pL = lightSamples > 0 ? lightPdf(l, sp, w, lightHit.p, lightHit.ng) : 0.f;
      const float weight = misWeight<kHeuristic>(nB * bsdfPdf(local.z), nL * pL);
      E += Le * (kPi * weight);  // cos θ / pdf = π
    }
    return E * (1.f / nB);
  }
};

}  // namespace penumbra
