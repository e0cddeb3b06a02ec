// Ambient occlusion: AO(x) = (1/pi) * integral over the hemisphere of V(x, w) cos(theta) dw,
// estimated with `samples` directions from the uniform (pdf 1/2pi) or cosine (pdf cos/pi) warp.
// Visibility rays stop at the scene's extent; albedo is not applied (as in the assignment's framework).
#pragma once

#include "core/integrators/integrator_desc.h"
#include "core/integrators/shading_point.h"
#include "core/sampling/sampler.h"
#include "core/sampling/warp.h"

namespace penumbra {

template <HemisphereWarp kWarp>
struct AoIntegrator {
  int samples = 1;

  Color3 Li(const Scene& scene, const Ray& ray, Sampler& sampler) const {
    float sum = 0.f;
    forEachVisibilityRay(scene, ray, sampler, [&](const Ray& shadow, float contribution) {
      if (!scene.geometry.occluded(shadow)) sum += contribution;
    });
    return radiance(sum);
  }

  // The estimate in two steps, so that a batch of camera samples can trace its visibility rays
  // together (core/render/ao_batch_row_loop.h): f(ray, contribution) for each direction that needs a
  // visibility test, in sampling order; the estimate is radiance(sum of the contributions of the
  // rays that were not occluded), added in that order (the image is the same as Li's, bit for bit).
  // `draws` is the Sampler, or anything else with its next2D(j, n) that gives the same values.
  template <class Draws, class F>
  [[gnu::always_inline]] void forEachVisibilityRay(const Scene& scene, const Ray& ray, Draws& draws,
                                                   F&& f) const {
    SurfaceHit hit;
    if (scene.geometry.intersect(ray, hit)) forEachVisibilityRayAt(scene, ray, hit, draws, f);
  }
  // The same from the camera ray's hit, found beforehand (with others, by SceneGeometry::intersectMany).
  template <class Draws, class F>
  [[gnu::always_inline]] void forEachVisibilityRayAt(const Scene& scene, const Ray& ray,
                                                     const SurfaceHit& hit, Draws& draws, F&& f) const {
    ShadingPoint sp(scene, ray, hit);
    for (int i = 0; i < samples; ++i) {
      Vec2 u = draws.next2D(uint32_t(i), uint32_t(samples));  // one request: stratified among themselves
      Vec3 local = kWarp == HemisphereWarp::Cosine ? Warp::squareToCosineHemisphere(u)
                                                   : Warp::squareToUniformHemisphere(u);
      Vec3 w = sp.frame.toWorld(local);
      if (glm::dot(w, sp.ng) <= 0.f) continue;  // below the true surface: blocked by it
      // V cos / (pi pdf): 1 for cosine sampling, 2 cos for uniform sampling.
      f(sp.spawnRay(w, scene.rayLengthBound), kWarp == HemisphereWarp::Cosine ? 1.f : 2.f * local.z);
    }
  }
  Color3 radiance(float sum) const { return Color3(sum * (1.f / float(samples))); }
};

}  // namespace penumbra
