// Direct illumination from all emitters:
//   Lr(x, wo) = sum over delta lights of f Li cos θ  +  integral of Le(x, w) f(wo, w) cos θ dw,
// on a diffuse surface albedo/π times the irradiance (reflection.h).
// Point and directional lights are evaluated deterministically. The area-light integral uses the
// strategy chosen at compile time (one instantiation per combination of the axes, so no per-sample
// branching):
//   hemisphere (uniform or cosine warp): trace the sampled direction, add Le of an emitter it hits;
//   bsdf: the same with the surface's own directions (the cosine warp on a diffuse surface);
//   area: a uniform point on each light (sphere or polygon), pdf converted to solid angle (a sphere's
//   far side adds 0);
//   solid angle: a uniform direction in the cone a sphere subtends, a polygon's spherical triangle or
//   rectangle;
//   projected solid angle: a direction in that solid angle with density cos θ / Ω⊥ above the horizon,
//   whose estimate Le Ω⊥ has no variance where the light is unoccluded on a diffuse surface (on a
//   glossy one, Le f Ω⊥ varies with f).
// The three light measures sample every light per shading sample (light selection `all`), or one
// light chosen per shading sample (uniform, by power, by the light BVH), its probability divided out.
// `simple` renders the delta lights alone.
#pragma once

#include <cmath>

#include "core/integrators/direct_lighting.h"
#include "core/integrators/integrator_desc.h"
#include "core/integrators/light_technique.h"
#include "core/integrators/sampling_loops.h"
#include "core/integrators/shading_point.h"
#include "core/sampling/sampler.h"
#include "core/sampling/warp.h"

namespace penumbra {

// Delta lights only (`simple`).
struct SimpleIntegrator {
  Color3 Li(const Scene& scene, const Ray& ray, Sampler&) const {
    return directRadiance<false>(scene, ray, [](const ShadingPoint&, const auto&) { return Color3(0.f); });
  }
};

// The area-light integral by hemisphere directions of warp kWarp, traced to the lights they hit.
template <HemisphereWarp kWarp>
struct HemisphereDirectIntegrator {
  int samples = 1;

  Color3 Li(const Scene& scene, const Ray& ray, Sampler& sampler) const {
    return directRadiance<true>(scene, ray, [&](const ShadingPoint& sp, const auto& reflection) {
      if (!scene.hasAreaLights()) return Color3(0.f);
      return hemisphereIrradiance<kWarp>(scene, sp, reflection, sampler, samples, UnitWeight{});
    });
  }
};

// The area-light integral by the surface's own direction sampling (`bsdf`), traced to the lights.
struct BsdfDirectIntegrator {
  int samples = 1;

  Color3 Li(const Scene& scene, const Ray& ray, Sampler& sampler) const {
    return directRadiance<true>(scene, ray, [&](const ShadingPoint& sp, const auto& reflection) {
      if (!scene.hasAreaLights()) return Color3(0.f);
      return surfaceSampledRadiance(scene, sp, reflection, sampler, samples, UnitWeight{});
    });
  }
};

// The area-light integral by light sampling of measure kMeasure: every light per shading sample
// (kSelection All) or one light chosen per shading sample.
template <LightMeasure kLightMeasure, LightSelection kSelection>
struct LightDirectIntegrator {
  int samples = 1;

  Color3 Li(const Scene& scene, const Ray& ray, Sampler& sampler) const {
    return directRadiance<false>(scene, ray, [&](const ShadingPoint& sp, const auto& reflection) {
      if constexpr (kSelection == LightSelection::Uniform) {
        return selectedLightIrradiance(scene, scene.uniformSelection, sp, reflection, sampler);
      } else if constexpr (kSelection == LightSelection::Power) {
        return selectedLightIrradiance(scene, scene.powerSelection, sp, reflection, sampler);
      } else if constexpr (kSelection == LightSelection::Bvh) {
        return selectedLightIrradiance(scene, scene.lightBvh, sp, reflection, sampler);
      } else {
        return everyLightIrradiance<kLightMeasure>(scene, sp, reflection, sampler, samples, UnitWeight{});
      }
    });
  }

 private:
  // One light per shading sample, chosen by `selection` with probability pick.pmf, then sampled by
  // this strategy's measure: Le cos / (pdf · pmf) is unbiased for the sum over all lights.
  template <class Selection, class Reflection>
  Color3 selectedLightIrradiance(const Scene& scene, const Selection& selection, const ShadingPoint& sp,
                                 const Reflection& reflection, Sampler& sampler) const {
    Color3 E(0.f);
    for (int i = 0; i < samples; ++i) {
      // Two sampler dimensions give the choice 48 bits: a 24-bit float would quantise deep BVHs and
      // large alias tables. Two interleaved requests (the choice, then the point on the light), each
      // stratified over the n shading samples.
      const Vec2 uPick = sampler.next2D(uint32_t(i), uint32_t(samples), 0, 2);
      const Vec2 u = sampler.next2D(uint32_t(i), uint32_t(samples), 1, 2);
      const LightPick pick = selection.pick(sp.hit.p, sp.ns, double(uPick.x) + double(uPick.y) * 0x1p-24);
      if (!(pick.pmf > 0.0)) continue;
      const size_t spheres = scene.sphereLights.size();
      if (pick.light < spheres)
        E += selectedLightSample<kLightMeasure>(scene, scene.sphereLights[pick.light], sp, reflection, u,
                                                pick.pmf);
      else
        E += selectedLightSample<kLightMeasure>(scene, scene.polygonLights[pick.light - spheres], sp,
                                                reflection, u, pick.pmf);
    }
    return E * (1.f / float(samples));
  }
};

}  // namespace penumbra
