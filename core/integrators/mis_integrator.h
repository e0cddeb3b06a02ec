// Direct illumination by multiple importance sampling (Veach's thesis, ch. 9, the multi-sample
// model): the area-light integral ∫ Le f cos θ dω is estimated with two techniques at once,
//   light sampling: for every area light (sphere or polygon), `lightSamples` directions of the light measure
//                   (area, solid angle or projected solid angle), and
//   BSDF sampling:  `bsdfSamples` directions of the surface's own sampler (cosine hemisphere on a diffuse
//                   surface, the BSDF's on a glossy one) shared by all lights, a direction that reaches a
//                   light unoccluded counting for that light,
// each sample weighted by the balance or power (β = 2) heuristic of the two techniques' solid-angle
// densities there: F = Σ_t (1/n_t) Σ_j w_t(ω_tj) f(ω_tj) / p_t(ω_tj), with w_L + w_B = 1 for every
// direction both can produce. A count of 0 turns the other technique into the plain estimator
// (bit for bit: its weights are then exactly 1). Point and directional lights are deterministic.
//
// Several area lights: every light is sampled (the loop of `lightSelection` `all`), none is chosen
// by a light selection, so MIS takes no `lightSelection`. The weight of a BSDF-sampled direction
// that reaches light L needs the density with which light sampling would have produced it: L's
// selection probability times the technique's pdf. With the loop that probability is 1, the weights
// are per light (a traced direction reaches one light, the nearest) and no selection pmf has to
// be evaluated at every hemisphere hit; selecting one light per sample pays off only for many lights.
#pragma once

#include <cmath>

#include "core/integrators/direct_lighting.h"
#include "core/integrators/light_technique.h"
#include "core/integrators/mis_weight.h"
#include "core/integrators/sampling_loops.h"
#include "core/integrators/shading_point.h"
#include "core/sampling/sampler.h"
#include "core/sampling/warp.h"

namespace penumbra {

template <LightMeasure kMeasure, MisHeuristic kHeuristic>
struct MisIntegrator {
  int lightSamples = 1;  // per area light, per camera sample
  int bsdfSamples = 1;   // BSDF-sampled directions per camera sample

  Color3 Li(const Scene& scene, const Ray& ray, Sampler& sampler) const {
    return directRadiance<true>(scene, ray, [&](const ShadingPoint& sp, const auto& reflection) {
      if (!scene.hasAreaLights()) return Color3(0.f);
      Color3 lightPart, bsdfPart;
      techniques(scene, sp, reflection, sampler, lightPart, bsdfPart);
      return lightPart + bsdfPart;
    });
  }

  // The two techniques' weighted estimates at a shading point (their sum is the estimate; each alone
  // is what the technique contributes to it): irradiance on a diffuse surface, reflected radiance on a
  // glossy one (reflection.h).
  template <class Reflection>
  void techniques(const Scene& scene, const ShadingPoint& sp, const Reflection& reflection, Sampler& sampler,
                  Color3& lightPart, Color3& bsdfPart) const {
    lightPart = lightSamples > 0 ? lightTechnique(scene, sp, reflection, sampler) : Color3(0.f);
    bsdfPart = bsdfSamples > 0 ? bsdfTechnique(scene, sp, reflection, sampler) : Color3(0.f);
  }

  // The density of the light technique for light `l` of a direction w reaching that light at p
  // (normal n); with the BSDF technique's (Reflection::pdf) the pair every weight is computed from.
  template <class Light>
  static float lightPdf(const Light& l, const ShadingPoint& sp, const Vec3& w, const Vec3& p, const Vec3& n) {
    return LightTechnique<kMeasure, Light>(l, sp).pdf(w, p, n);
  }

 private:
  template <class Reflection>
  Color3 lightTechnique(const Scene& scene, const ShadingPoint& sp, const Reflection& reflection,
                        Sampler& sampler) const {
    const float nL = float(lightSamples), nB = float(bsdfSamples);
    return everyLightIrradiance<kMeasure>(
        scene, sp, reflection, sampler, lightSamples, [&](const LightSample& s, float cosTheta) {
          return misWeight<kHeuristic>(nL * s.pdf, nB * reflection.pdf(s.wi, cosTheta));
        });
  }

  template <class Reflection>
  Color3 bsdfTechnique(const Scene& scene, const ShadingPoint& sp, const Reflection& reflection,
                       Sampler& sampler) const {
    const float nL = float(lightSamples), nB = float(bsdfSamples);
    return surfaceSampledRadiance(
        scene, sp, reflection, sampler, bsdfSamples,
        [&](const auto& light, const SurfaceHit& lightHit, const Vec3& w, float pdf) {
          const float pL = lightSamples > 0 ? lightPdf(light, sp, w, lightHit.p, lightHit.ng) : 0.f;
          return misWeight<kHeuristic>(nB * pdf, nL * pL);
        });
  }
};

}  // namespace penumbra
