// The MIS integrator's estimate split by technique, for the viewer's "MIS light share" view: per
// camera sample the luminance of the weighted light-sampling part (R), of the weighted
// BSDF-sampling part (G) and of everything else (B: point and directional lights; on a light seen
// directly, its whole estimate). The three add up to the luminance of MisIntegrator::Li for the same sample
// stream, so the film's per-pixel means give the share of the area-light estimate that light sampling
// contributes, E[R] / (E[R] + E[G]) (lightShare below). A separate instance of the row loop (the strategy
// table's makeLightShareRows): no other strategy, and no ordinary mis render, pays for it.
#pragma once

#include <algorithm>

#include "core/integrators/mis_integrator.h"
#include "core/integrators/shading_point.h"

namespace penumbra {

template <LightMeasure kMeasure, MisHeuristic kHeuristic>
struct MisLightShareIntegrator {
  MisIntegrator<kMeasure, kHeuristic> mis;

  // The steps of MisIntegrator::Li, with the same sampler calls in the same order (tested: the
  // channels' sum equals the luminance of its image).
  Color3 Li(const Scene& scene, const Ray& ray, Sampler& sampler) const {
    SurfaceHit hit;
    if (!scene.geometry.intersect(ray, hit)) return Color3(0.f);
    const SurfaceMaterial& material = scene.materials[hit.objectId];
    const Color3 L = emittedAt(scene, material, hit, ray);
    if (!material.bsdf.reflects()) return Color3(0.f, 0.f, luminance(L));

    ShadingPoint sp(scene, ray, hit);
    if (material.bsdf.isDiffuse())
      return shares(scene, sp, material, L, DiffuseReflection{}, material.bsdf.albedo * kInvPi, sampler);
    return shares(scene, sp, material, L, GlossyReflection(material.bsdf, sp, ray.d), Color3(1.f), sampler);
  }

 private:
  // The three channels from the techniques' estimates, each times `scale` (albedo/π on a diffuse
  // surface, whose estimates are irradiance; 1 on a glossy one).
  template <class Reflection>
  Color3 shares(const Scene& scene, const ShadingPoint& sp, const SurfaceMaterial& material, const Color3& L,
                const Reflection& reflection, const Color3& scale, Sampler& sampler) const {
    const Color3 delta = deltaIrradiance(scene, sp, reflection);
    Color3 lightPart(0.f), bsdfPart(0.f);
    if (scene.hasAreaLights()) mis.techniques(scene, sp, reflection, sampler, lightPart, bsdfPart);
    // A light seen directly: its emission outshines what it reflects, so the whole estimate counts as
    // "the rest" and the view shows the light as having no share.
    if (material.emits()) return Color3(0.f, 0.f, luminance(L + scale * (delta + (lightPart + bsdfPart))));
    return Color3(luminance(scale * lightPart), luminance(scale * bsdfPart), luminance(L + scale * delta));
  }
};

// The light technique's share of a pixel's area-light estimate from the mean of a light-share film,
// E[R] / (E[R] + E[G]) in [0, 1], or a negative value when the pixel has no area light to share
// (R + G <= 0, or not finite). Clamped: a pixel filter with negative lobes (mitchell) can push the
// ratio of the weighted sums slightly outside.
inline float lightShare(const Color3& mean) {
  const float total = mean.x + mean.y;
  if (!(total > 0.f) || !(total < INFINITY)) return -1.f;
  return std::clamp(mean.x / total, 0.f, 1.f);
}

}  // namespace penumbra
