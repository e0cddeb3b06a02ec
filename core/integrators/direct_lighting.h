// What every direct-lighting estimator shares: which directions can carry light to a shading point,
// the deterministic contribution of point and directional lights, and the radiance of a camera ray
// made from them and a strategy's estimate of the area-light integral.
#pragma once

#include "core/integrators/shading_point.h"

namespace penumbra {

// A direction w (with cosine `cosTheta` to the shading normal) can carry light only if it also
// leaves the geometric surface on the lit side.
inline bool leavesSurface(const ShadingPoint& sp, const Vec3& w, float cosTheta) {
  return cosTheta > 0.f && glm::dot(w, sp.ng) > 0.f;
}

// Irradiance from the point and directional lights, each traced once (they are deltas: no sampling).
// Always inlined: once per shading point, and GCC stops inlining it into the larger integrators.
[[gnu::always_inline]] inline Color3 deltaIrradiance(const Scene& scene, const ShadingPoint& sp) {
  Color3 E(0.f);
  for (const PointLight& light : scene.pointLights) {
    DeltaLightSample s = light.sample(sp.hit.p);
    float cosTheta = glm::dot(sp.ns, s.wi);
    if (isBlack(s.Li) || !leavesSurface(sp, s.wi, cosTheta)) continue;
    if (scene.geometry.occluded(sp.spawnShadowRayToPoint(light.position, maxAbsComponent(light.position))))
      continue;
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

// The radiance along a camera ray by direct lighting on a diffuse surface: what the first surface
// emits towards the camera plus albedo/π times its irradiance from the delta lights and
// areaIrradiance(sp), the strategy's estimate of the area-light integral. kWithFrame: whether that
// estimate samples about the normal (ShadingPoint's frame).
template <bool kWithFrame, class AreaIrradiance>
[[gnu::always_inline]] inline Color3 directRadiance(const Scene& scene, const Ray& ray,
                                                    const AreaIrradiance& areaIrradiance) {
  SurfaceHit hit;
  if (!scene.geometry.intersect(ray, hit)) return Color3(0.f);
  const SurfaceMaterial& material = scene.materials[hit.objectId];
  const Color3 L = emittedAt(scene, material, hit, ray);
  if (isBlack(material.albedo)) return L;

  ShadingPoint sp(scene, ray, hit, kWithFrame);
  Color3 E = deltaIrradiance(scene, sp);
  E += areaIrradiance(sp);
  return L + material.albedo * kInvPi * E;
}

}  // namespace penumbra
