// What every integrator derives from a camera hit: the hit, its material, normals facing the viewer
// (surfaces are two-sided for reflection; emitters stay one-sided) and the shading frame.
#pragma once

#include "core/geometry/ray.h"
#include "core/geometry/surface_hit.h"
#include "core/math/float_util.h"
#include "core/math/frame.h"
#include "core/world/scene.h"

namespace penumbra {

// The emission seen along `ray` at its hit: the light's radiance there (on its emitting side), 0 on
// other surfaces.
[[gnu::always_inline]] inline Color3 emittedAt(const Scene& scene, const SurfaceMaterial& material,
                                               const SurfaceHit& hit, const Ray& ray) {
  if (material.sphereLight >= 0) return scene.sphereLights[material.sphereLight].eval(hit.p, hit.ng, ray.d);
  if (material.polygonLightsAt < 0) return Color3(0.f);
  const PolygonLight* light = scene.polygonLightOf(material, hit.primId);
  return light ? light->eval(ray.d) : Color3(0.f);
}

struct ShadingPoint {
  SurfaceHit hit;
  Vec3 ng, ns;  // flipped to the side the ray came from
  Frame frame;  // around ns (identity when built without it)
  const SurfaceMaterial* material;

  // withFrame = false skips the shading frame for estimators that never sample around the normal.
  // Always inlined (once per camera sample; GCC stops inlining it into the larger integrators).
  [[gnu::always_inline]] ShadingPoint(const Scene& scene, const Ray& ray, const SurfaceHit& h,
                                      bool withFrame = true)
      : hit(h) {
    material = &scene.materials[h.objectId];
    bool backFacing = glm::dot(h.ng, ray.d) > 0.f;
    ng = backFacing ? -h.ng : h.ng;
    ns = backFacing ? -h.ns : h.ns;
    if (glm::dot(ns, ng) < 0.f) ns = ng;  // interpolated normal pointing inside: fall back to geometry
    if (withFrame) frame = Frame(ns);
  }

  // The shading point at p whose normals are already flipped to the viewer's side (as the constructor
  // above leaves them), without frame or material: what light sampling reads of it.
  static ShadingPoint facing(const Vec3& p, const Vec3& ng, const Vec3& ns, float offsetScale) {
    return ShadingPoint(p, ng, ns, offsetScale);
  }

  // A ray leaving the surface towards unit direction w, up to distance tMax.
  Ray spawnRay(const Vec3& w, float tMax) const {
    Ray r;
    r.o = offsetRayOrigin(hit.p, ng, hit.offsetScale, w);
    r.d = w;
    r.tMin = 0.f;
    r.tMax = tMax;
    return r;
  }

  // A shadow ray to point `target` (e.g. a point light), its direction and length measured from the
  // offset origin; it stops short of the target by the target's own offset so that the light's
  // surface does not occlude itself.
  Ray spawnShadowRayToPoint(const Vec3& target, float targetScale) const {
    Ray r;
    r.o = offsetRayOrigin(hit.p, ng, hit.offsetScale, target - hit.p);
    Vec3 d = target - r.o;
    float dist = glm::length(d);
    r.d = d * (1.f / dist);
    r.tMin = 0.f;
    r.tMax = dist - 2.f * kRayOffsetScale * std::max(targetScale, hit.offsetScale);
    return r;
  }

  // A shadow ray along unit direction w for distance `dist`, both already known from hit.p to the
  // target (light sampling computes them): no square root or division on the critical path.
  // The origin moves by the offset, so the ray may pass the target by that much sideways; it stops
  // short by that much more.
  Ray spawnShadowRayAlong(const Vec3& w, float dist, float targetScale) const {
    Ray r;
    r.o = offsetRayOrigin(hit.p, ng, hit.offsetScale, w);
    r.d = w;
    r.tMin = 0.f;
    r.tMax = dist - kRayOffsetScale * (2.f * std::max(targetScale, hit.offsetScale) + hit.offsetScale);
    return r;
  }

 private:
  ShadingPoint(const Vec3& p, const Vec3& facingNg, const Vec3& facingNs, float offsetScale)
      : ng(facingNg), ns(facingNs), material(nullptr) {
    hit.p = p;
    hit.ng = facingNg;
    hit.ns = facingNs;
    hit.offsetScale = offsetScale;
  }
};

}  // namespace penumbra
