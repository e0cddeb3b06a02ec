// What every direct-lighting estimator shares: which directions can carry light to a shading point,
// the deterministic contribution of point and directional lights, and the radiance of a camera ray
// made from them and a strategy's estimate of the area-light integral.
#pragma once

#include "core/integrators/reflection.h"
#include "core/integrators/shading_point.h"

namespace penumbra {

// A direction w (with cosine `cosTheta` to the shading normal) can carry light only if it also
// leaves the geometric surface on the lit side.
inline bool leavesSurface(const ShadingPoint& sp, const Vec3& w, float cosTheta) {
  return cosTheta > 0.f && glm::dot(w, sp.ng) > 0.f;
}

// Irradiance from the point and directional lights, each traced once (they are deltas: no sampling),
// each term times the reflection's factor (reflection.h: 1 on a diffuse surface, f on a glossy one).
// Always inlined: once per shading point, and GCC stops inlining it into the larger integrators.
template <class Reflection>
[[gnu::always_inline]] inline Color3 deltaIrradiance(const Scene& scene, const ShadingPoint& sp,
                                                     const Reflection& reflection) {
  Color3 E(0.f);
  for (const PointLight& light : scene.pointLights) {
    DeltaLightSample s = light.sample(sp.hit.p);
    float cosTheta = glm::dot(sp.ns, s.wi);
    if (isBlack(s.Li) || !leavesSurface(sp, s.wi, cosTheta)) continue;
    if (scene.geometry.occluded(sp.spawnShadowRayToPoint(light.position, maxAbsComponent(light.position))))
      continue;
    E += reflection(s.Li, s.wi) * cosTheta;
  }
  for (const DirectionalLight& light : scene.directionalLights) {
    DeltaLightSample s = light.sample(sp.hit.p);
    float cosTheta = glm::dot(sp.ns, s.wi);
    if (isBlack(s.Li) || !leavesSurface(sp, s.wi, cosTheta)) continue;
    if (scene.geometry.occluded(sp.spawnRay(s.wi, scene.rayLengthBound))) continue;
    E += reflection(s.Li, s.wi) * cosTheta;
  }
  return E;
}

// The radiance along a camera ray by direct lighting: what the first surface emits towards the camera
// plus what it reflects from the delta lights and from the area lights, whose integral
// areaEstimate(sp, reflection) estimates by the strategy's technique. On a diffuse surface the
// estimates are irradiance and albedo/π multiplies their sum; on a glossy one each sample already
// carries f. kWithFrame: whether a diffuse surface's estimate samples about the normal (ShadingPoint's
// frame; glossy surfaces always build it).
template <bool kWithFrame, class AreaEstimate>
[[gnu::always_inline]] inline Color3 directRadiance(const Scene& scene, const Ray& ray,
                                                    const AreaEstimate& areaEstimate) {
  SurfaceHit hit;
  if (!scene.geometry.intersect(ray, hit)) return Color3(0.f);
  const SurfaceMaterial& material = scene.materials[hit.objectId];
  const Color3 L = emittedAt(scene, material, hit, ray);
  // The diffuse path first and on its own test of the albedo: what every diffuse scene ran before.
  if (material.bsdf.isDiffuse()) [[likely]] {
    if (isBlack(material.bsdf.albedo)) return L;
    ShadingPoint sp(scene, ray, hit, kWithFrame);
    const DiffuseReflection diffuse;
    Color3 E = deltaIrradiance(scene, sp, diffuse);
    E += areaEstimate(sp, diffuse);
    return L + material.bsdf.albedo * kInvPi * E;
  }
  if (!material.bsdf.reflects()) return L;
  ShadingPoint sp(scene, ray, hit);
  const GlossyReflection glossy(material.bsdf, sp, ray.d);
  return L + deltaIrradiance(scene, sp, glossy) + areaEstimate(sp, glossy);
}

}  // namespace penumbra
