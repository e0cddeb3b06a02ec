#include "core/render/packet_queries.h"

#include "core/integrators/reflection.h"
#include "core/integrators/sampling_loops.h"
#include "core/integrators/shading_point.h"
#include "core/world/scene.h"

namespace penumbra {

namespace {

Vec3 lane(const float (&v)[3][kMaxPacketLanes], int k) {
  return Vec3(v[0][k], v[1][k], v[2][k]);
}

void setLane(float (&v)[3][kMaxPacketLanes], int k, const Vec3& x) {
  v[0][k] = x.x, v[1][k] = x.y, v[2][k] = x.z;
}

// The segment of lane k as the scalar integrators build it (ShadingPoint::spawnRay and the shadow rays:
// tMin 0).
Ray segment(const PacketSegments& rays, int k) {
  Ray r;
  r.o = lane(rays.o, k);
  r.d = lane(rays.d, k);
  r.tMin = 0.f;
  r.tMax = rays.tMax[k];
  return r;
}

// Lane k's shading point.
ShadingPoint shadingPoint(const PacketShadingLanes& points, int k) {
  return ShadingPoint::facing(lane(points.p, k), lane(points.ng, k), lane(points.ns, k),
                              points.offsetScale[k]);
}

Vec2 drawOf(const float (&u)[2][kMaxPacketLanes], int k) {
  return Vec2(u[0][k], u[1][k]);
}

template <LightMeasure kMeasure, class Light>
void addLightIrradiance(const Scene& scene, const Light& light, size_t firstDraw,
                        const PacketShadingLanes& points, const PacketDraws& draws, int samples, int lanes,
                        PacketColorLanes& E) {
  const float lightScale = lightScaleOf(light);
  for (int k = 0; k < lanes; ++k) {
    if (points.active[k] == 0.f) continue;
    const ShadingPoint sp = shadingPoint(points, k);
    const LightTechnique<kMeasure, Light> technique(light, sp);
    Color3 e = lane(E.c, k);
    for (int i = 0; i < samples; ++i)
      addLightDraw(scene, light, lightScale, technique, sp, DiffuseReflection{},
                   drawOf(draws.u[firstDraw + size_t(i)], k), UnitWeight{}, e);
    setLane(E.c, k, e);
  }
}

template <LightMeasure kMeasure>
void lightIrradiance(const Scene& scene, size_t firstLight, const PacketShadingLanes& points,
                     const PacketDraws& draws, int samples, int lanes, PacketColorLanes& E) {
  const size_t spheres = scene.sphereLights.size(), count = scene.areaLightCount();
  for (size_t l = firstLight; l < count; ++l) {
    const size_t firstDraw = l * size_t(samples);
    if (l < spheres)
      addLightIrradiance<kMeasure>(scene, scene.sphereLights[l], firstDraw, points, draws, samples, lanes, E);
    else
      addLightIrradiance<kMeasure>(scene, scene.polygonLights[l - spheres], firstDraw, points, draws, samples,
                                   lanes, E);
  }
}

template <LightMeasure kMeasure>
void selectedLightSamples(const Scene& scene, const PacketShadingLanes& points, const PacketPickLanes& picks,
                          const float (&u)[2][kMaxPacketLanes], int lanes, PacketColorLanes& out) {
  const size_t spheres = scene.sphereLights.size();
  for (int k = 0; k < lanes; ++k) {
    Color3 c(0.f);
    if (points.active[k] != 0.f && picks.light[k] >= 0.f) {
      const ShadingPoint sp = shadingPoint(points, k);
      const size_t l = size_t(picks.light[k]);
      c = l < spheres ? selectedLightSample<kMeasure>(scene, scene.sphereLights[l], sp, DiffuseReflection{},
                                                      drawOf(u, k), picks.pmf[k])
                      : selectedLightSample<kMeasure>(scene, scene.polygonLights[l - spheres], sp,
                                                      DiffuseReflection{}, drawOf(u, k), picks.pmf[k]);
    }
    setLane(out.c, k, c);
  }
}

}  // namespace

void queryLightIrradiance(const Scene& scene, LightMeasure measure, size_t firstLight,
                          const PacketShadingLanes& points, const PacketDraws& draws, int samples, int lanes,
                          PacketColorLanes& E) {
  switch (measure) {
    case LightMeasure::Area:
      return lightIrradiance<LightMeasure::Area>(scene, firstLight, points, draws, samples, lanes, E);
    case LightMeasure::SolidAngle:
      return lightIrradiance<LightMeasure::SolidAngle>(scene, firstLight, points, draws, samples, lanes, E);
    case LightMeasure::ProjectedSolidAngle:
      return lightIrradiance<LightMeasure::ProjectedSolidAngle>(scene, firstLight, points, draws, samples,
                                                                lanes, E);
  }
}

void querySelectedLightSamples(const Scene& scene, LightMeasure measure, const PacketShadingLanes& points,
                               const PacketPickLanes& picks, const float (&u)[2][kMaxPacketLanes], int lanes,
                               PacketColorLanes& out) {
  switch (measure) {
    case LightMeasure::Area:
      return selectedLightSamples<LightMeasure::Area>(scene, points, picks, u, lanes, out);
    case LightMeasure::SolidAngle:
      return selectedLightSamples<LightMeasure::SolidAngle>(scene, points, picks, u, lanes, out);
    case LightMeasure::ProjectedSolidAngle:
      return selectedLightSamples<LightMeasure::ProjectedSolidAngle>(scene, points, picks, u, lanes, out);
  }
}

void queryCameraHits(const Scene& scene, const PacketRays& rays, int lanes, PacketHitLanes& out) {
  for (int k = 0; k < lanes; ++k) {
    Ray ray;
    ray.o = lane(rays.o, k);
    ray.d = lane(rays.d, k);
    ray.tMin = rays.tMin[k];
    ray.tMax = rays.tMax[k];
    SurfaceHit hit;
    if (!scene.geometry.intersect(ray, hit)) {
      out.hit[k] = out.offsetScale[k] = out.shades[k] = 0.f;
      for (auto* v : {&out.p, &out.ng, &out.ns, &out.nsHit, &out.albedoOverPi, &out.emitted})
        setLane(*v, k, Vec3(0.f));
      continue;
    }
    const SurfaceMaterial& material = scene.materials[hit.objectId];
    const ShadingPoint sp(scene, ray, hit, false);
    out.hit[k] = 1.f;
    setLane(out.p, k, hit.p);
    setLane(out.ng, k, sp.ng);
    setLane(out.ns, k, sp.ns);
    setLane(out.nsHit, k, hit.ns);
    out.offsetScale[k] = hit.offsetScale;
    out.shades[k] = isBlack(material.bsdf.albedo) ? 0.f : 1.f;
    setLane(out.albedoOverPi, k, material.bsdf.albedo * kInvPi);
    setLane(out.emitted, k, emittedAt(scene, material, hit, ray));
  }
}

void queryOccluded(const Scene& scene, const PacketSegments& rays, int lanes, int32_t skipSphere,
                   float* blocked) {
  Ray segments[kMaxPacketLanes];
  // Zeroed: the compiler cannot see that lanes <= kMaxPacketLanes.
  bool active[kMaxPacketLanes] = {}, hit[kMaxPacketLanes];
  for (int k = 0; k < lanes; ++k) {
    segments[k] = segment(rays, k);
    active[k] = rays.active[k] != 0.f;
  }
  scene.geometry.occludedMany(segments, active, size_t(lanes), skipSphere, hit);
  for (int k = 0; k < lanes; ++k) blocked[k] = hit[k] ? 1.f : 0.f;
}

void queryEmittersAlong(const Scene& scene, const PacketSegments& rays, int lanes, PacketEmitterLanes& out) {
  for (int k = 0; k < lanes; ++k) {
    out.light[k] = -1.f;
    SurfaceHit hit;
    if (rays.active[k] == 0.f) continue;
    const Ray ray = segment(rays, k);
    if (!scene.geometry.intersect(ray, hit)) continue;
    // addEmitterAlong: a sphere light's outer side, a polygon light's emitting side.
    const SurfaceMaterial& material = scene.materials[hit.objectId];
    size_t light;
    Color3 Le;
    if (material.sphereLight >= 0) {
      light = size_t(material.sphereLight);
      Le = scene.sphereLights[light].eval(hit.p, hit.ng, ray.d);
    } else if (const PolygonLight* polygon = scene.polygonLightOf(material, hit.primId)) {
      light = scene.sphereLights.size() + size_t(polygon - scene.polygonLights.data());
      Le = polygon->eval(ray.d);
    } else {
      continue;
    }
    if (isBlack(Le)) continue;
    out.light[k] = float(light);
    setLane(out.Le, k, Le);
    setLane(out.p, k, hit.p);
    setLane(out.ng, k, hit.ng);
  }
}

namespace {

template <class Selection>
void pickLights(const Selection& selection, const float (&u)[2][kMaxPacketLanes], int lanes,
                PacketPickLanes& picks) {
  for (int k = 0; k < lanes; ++k) {
    picks.light[k] = -1.f;
    picks.pmf[k] = 0.0;
    if (picks.active[k] == 0.f) continue;
    const LightPick pick =
        selection.pick(lane(picks.p, k), lane(picks.n, k), double(u[0][k]) + double(u[1][k]) * 0x1p-24);
    if (!(pick.pmf > 0.0)) continue;
    picks.light[k] = float(pick.light);
    picks.pmf[k] = pick.pmf;
  }
}

}  // namespace

void queryLightPicks(const Scene& scene, LightSelection selection, const float (&u)[2][kMaxPacketLanes],
                     int lanes, PacketPickLanes& picks) {
  switch (selection) {
    case LightSelection::Uniform:
      return pickLights(scene.uniformSelection, u, lanes, picks);
    case LightSelection::Power:
      return pickLights(scene.powerSelection, u, lanes, picks);
    case LightSelection::Bvh:
      return pickLights(scene.lightBvh, u, lanes, picks);
    case LightSelection::All:
      break;
  }
  for (int k = 0; k < lanes; ++k) picks.light[k] = -1.f, picks.pmf[k] = 0.0;
}

}  // namespace penumbra
