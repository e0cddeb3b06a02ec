// Direct illumination from all emitters onto diffuse surfaces:
//   Lr(x) = albedo/pi * [ sum over delta lights of E_i  +  integral of Le(x, w) cos(theta) dw ].
// Point and directional lights are evaluated deterministically. The area-light integral uses the
// strategy chosen at compile time (one instantiation per measure, so no per-sample branching):
//   hemisphere (uniform or cosine warp): trace the sampled direction, add Le of an emitter it hits;
//   area: a uniform point on each light sphere, pdf converted to solid angle (far side adds 0);
//   solid angle: a uniform direction in the cone each light sphere subtends.
// `simple` is the same integrator with delta lights only.
#pragma once

#include <cmath>

#include "core/integrators/integrator_desc.h"
#include "core/integrators/shading_point.h"
#include "core/sampling/sampler.h"
#include "core/sampling/warp.h"

namespace penumbra {

// kStrategy: Simple (delta lights only) or one of the Direct* strategies.
template <Strategy kStrategy>
struct DirectIntegrator {
  static_assert(kStrategy == Strategy::Simple || kStrategy == Strategy::DirectUniformHemisphere ||
                kStrategy == Strategy::DirectCosineHemisphere || kStrategy == Strategy::DirectArea ||
                kStrategy == Strategy::DirectSolidAngle);
  int samples = 1;

  Color3 Li(const Scene& scene, const Ray& ray, Sampler& sampler) const {
    SurfaceHit hit;
    if (!scene.geometry.intersect(ray, hit)) return Color3(0.f);
    const SurfaceMaterial& material = scene.materials[hit.objectId];
    Color3 L(0.f);
    if (material.sphereLight >= 0) L += scene.sphereLights[material.sphereLight].eval(hit.p, hit.ng, ray.d);
    if (isBlack(material.albedo)) return L;

    constexpr bool kSamplesHemisphere =
        kStrategy == Strategy::DirectUniformHemisphere || kStrategy == Strategy::DirectCosineHemisphere;
    ShadingPoint sp(scene, ray, hit, kSamplesHemisphere);
    Color3 E = deltaIrradiance(scene, sp);
    if constexpr (kSamplesHemisphere) {
      if (scene.hasAreaLights()) E += hemisphereIrradiance(scene, sp, sampler);
    } else if constexpr (kStrategy == Strategy::DirectArea || kStrategy == Strategy::DirectSolidAngle) {
      E += lightSamplingIrradiance(scene, sp, sampler);
    }
    return L + material.albedo * kInvPi * E;
  }

 private:
  // A direction w (with cosine `cosTheta` to the shading normal) can carry light only if it also
  // leaves the geometric surface on the lit side.
  static bool leavesSurface(const ShadingPoint& sp, const Vec3& w, float cosTheta) {
    return cosTheta > 0.f && glm::dot(w, sp.ng) > 0.f;
  }

  static Color3 deltaIrradiance(const Scene& scene, const ShadingPoint& sp) {
    Color3 E(0.f);
    for (const PointLight& light : scene.pointLights) {
      DeltaLightSample s = light.sample(sp.hit.p);
      float cosTheta = glm::dot(sp.ns, s.wi);
      if (isBlack(s.Li) || !leavesSurface(sp, s.wi, cosTheta)) continue;
      if (scene.geometry.occluded(sp.spawnRayTo(light.position, maxAbsComponent(light.position)))) continue;
      E += s.Li * cosTheta;
    }
    for (const DirectionalLight& light : scene.directionalLights) {
      DeltaLightSample s = light.sample(sp.hit.p);
      float cosTheta = glm::dot(sp.ns, s.wi);
      if (isBlack(s.Li) || !leavesSurface(sp, s.wi, cosTheta)) continue;
      if (scene.geometry.occluded(sp.spawnRay(s.wi, scene.rayLengthBound))) continue;
      E += s.Li * cosTheta;
    }
    return E;
  }

  Color3 hemisphereIrradiance(const Scene& scene, const ShadingPoint& sp, Sampler& sampler) const {
    Color3 E(0.f);
    for (int i = 0; i < samples; ++i) {
      Vec2 u = sampler.next2D(uint32_t(i), uint32_t(samples));  // one request: stratified among themselves
      Vec3 local;
      float cosOverPdf;  // cos θ / pdf, in closed form: π (cosine warp), 2π cos θ (uniform warp)
      if constexpr (kStrategy == Strategy::DirectCosineHemisphere) {
        local = Warp::squareToCosineHemisphere(u);
        if (!(local.z > 0.f)) continue;
        cosOverPdf = kPi;
      } else {
        local = Warp::squareToUniformHemisphere(u);
        cosOverPdf = 2.f * kPi * local.z;
      }
      Vec3 w = sp.frame.toWorld(local);
      if (!leavesSurface(sp, w, local.z)) continue;
      SurfaceHit lightHit;
      if (!scene.geometry.intersect(sp.spawnRay(w, INFINITY), lightHit)) continue;
      int32_t light = scene.materials[lightHit.objectId].sphereLight;
      if (light < 0) continue;
      E += scene.sphereLights[light].eval(lightHit.p, lightHit.ng, w) * cosOverPdf;
    }
    return E * (1.f / float(samples));  // the reciprocal is off the critical path
  }

  Color3 lightSamplingIrradiance(const Scene& scene, const ShadingPoint& sp, Sampler& sampler) const {
    Color3 E(0.f);
    for (const SphereLight& light : scene.sphereLights) {
      float lightScale = maxAbsComponent(light.sphere.center) + light.sphere.radius;
      for (int i = 0; i < samples; ++i) {
        Vec2 u = sampler.next2D(uint32_t(i), uint32_t(samples));  // one request per light
        LightSample s = kStrategy == Strategy::DirectArea ? light.sampleArea(sp.hit.p, u)
                                                          : light.sampleSolidAngle(sp.hit.p, u);
        if (!(s.pdf > 0.f) || isBlack(s.Le)) continue;
        float cosTheta = glm::dot(sp.ns, s.wi);
        if (!leavesSurface(sp, s.wi, cosTheta)) continue;
        // Every traced sample faces x (far-side area samples have Le = 0): the light cannot block it.
        if (scene.geometry.occluded(sp.spawnRayTowards(s.wi, s.dist, lightScale), light.geometryIndex))
          continue;
        E += s.Le * (cosTheta / s.pdf);
      }
    }
    return E * (1.f / float(samples));
  }
};

}  // namespace penumbra
