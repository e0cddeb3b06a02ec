#include "core/render/packet_queries.h"

#include <cassert>

#include "core/integrators/light_technique.h"
#include "core/integrators/polygon_light_technique.h"
#include "core/integrators/reflection.h"
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

template <LightMeasure kMeasure>
void lightPdfs(const Scene& scene, const PacketShadingLanes& points, const float (&light)[kMaxPacketLanes],
               const float (&w)[3][kMaxPacketLanes], const float (&p)[3][kMaxPacketLanes],
               const float (&n)[3][kMaxPacketLanes], int lanes, float* pdf) {
  const size_t spheres = scene.sphereLights.size();
  for (int k = 0; k < lanes; ++k) {
    pdf[k] = 0.f;
    if (points.active[k] == 0.f) continue;
    const ShadingPoint sp = shadingPoint(points, k);
    const size_t l = size_t(light[k]);
    pdf[k] = l < spheres ? LightTechnique<kMeasure, SphereLight>(scene.sphereLights[l], sp)
                               .pdf(lane(w, k), lane(p, k), lane(n, k))
                         : LightTechnique<kMeasure, PolygonLight>(scene.polygonLights[l - spheres], sp)
                               .pdf(lane(w, k), lane(p, k), lane(n, k));
  }
}

}  // namespace

void queryLightPdfs(const Scene& scene, LightMeasure measure, const PacketShadingLanes& points,
                    const float (&light)[kMaxPacketLanes], const float (&w)[3][kMaxPacketLanes],
                    const float (&p)[3][kMaxPacketLanes], const float (&n)[3][kMaxPacketLanes], int lanes,
                    float* pdf) {
  switch (measure) {
    case LightMeasure::Area:
      return lightPdfs<LightMeasure::Area>(scene, points, light, w, p, n, lanes, pdf);
    case LightMeasure::SolidAngle:
      return lightPdfs<LightMeasure::SolidAngle>(scene, points, light, w, p, n, lanes, pdf);
    case LightMeasure::ProjectedSolidAngle:
      return lightPdfs<LightMeasure::ProjectedSolidAngle>(scene, points, light, w, p, n, lanes, pdf);
  }
}

namespace {

// LightTechnique<kMeasure, Light>'s samples of `light` from draws firstDraw .. firstDraw + count − 1 at
// lane k's shading point, the technique set up once.
template <LightMeasure kMeasure, class Light>
void laneLightSamples(const Light& light, const ShadingPoint& sp, const PacketDraws& draws, size_t firstDraw,
                      int count, int k, PacketLightSampleLanes* out) {
  const LightTechnique<kMeasure, Light> technique(light, sp);
  if (!technique.canSample()) return;
  for (int i = 0; i < count; ++i) {
    const LightSample s = technique.sample(drawOf(draws.draw[firstDraw + size_t(i)].u, k));
    if (!(s.pdf > 0.f)) continue;
    setLane(out[i].wi, k, s.wi);
    out[i].dist[k] = s.dist;
    out[i].pdf[k] = s.pdf;
    if constexpr (kMeasure == LightMeasure::ProjectedSolidAngle)
      out[i].projected[k] = technique.cosOverPdf(s, 0.f);
  }
}

template <LightMeasure kMeasure>
void lightSamples(const Scene& scene, const float (&light)[kMaxPacketLanes], const PacketShadingLanes& points,
                  const PacketDraws& draws, size_t firstDraw, int count, int lanes,
                  PacketLightSampleLanes* out) {
  const size_t spheres = scene.sphereLights.size();
  for (int k = 0; k < lanes; ++k) {
    if (points.active[k] == 0.f || light[k] < 0.f) continue;
    const ShadingPoint sp = shadingPoint(points, k);
    const size_t l = size_t(light[k]);
    if (l < spheres)
      laneLightSamples<kMeasure>(scene.sphereLights[l], sp, draws, firstDraw, count, k, out);
    else
      laneLightSamples<kMeasure>(scene.polygonLights[l - spheres], sp, draws, firstDraw, count, k, out);
  }
}

}  // namespace

void queryLightSamples(const Scene& scene, LightMeasure measure, const float (&light)[kMaxPacketLanes],
                       const PacketShadingLanes& points, const PacketDraws& draws, size_t firstDraw,
                       int count, int lanes, PacketLightSampleLanes* out) {
  for (int i = 0; i < count; ++i) out[i] = PacketLightSampleLanes{};
  switch (measure) {
    case LightMeasure::Area:
      return lightSamples<LightMeasure::Area>(scene, light, points, draws, firstDraw, count, lanes, out);
    case LightMeasure::SolidAngle:
      return lightSamples<LightMeasure::SolidAngle>(scene, light, points, draws, firstDraw, count, lanes,
                                                    out);
    case LightMeasure::ProjectedSolidAngle:
      return lightSamples<LightMeasure::ProjectedSolidAngle>(scene, light, points, draws, firstDraw, count,
                                                             lanes, out);
  }
}

void queryCameraHits(const Scene& scene, const PacketRays* rays, int packets, int lanes,
                     PacketHitLanes* out) {
  Ray ray[kQueriedCameraRays];
  SurfaceHit hits[kQueriedCameraRays];
  bool found[kQueriedCameraRays];
  assert(packets * lanes <= kQueriedCameraRays);
  const int count = packets * lanes;
  for (int i = 0; i < count; ++i) ray[i] = cameraRay(rays[i / lanes], i % lanes);
  scene.geometry.intersectMany(ray, size_t(count), hits, found);
  for (int i = 0; i < count; ++i) {
    PacketHitLanes& lanesOut = out[i / lanes];
    const int k = i % lanes;
    const SurfaceHit& hit = hits[i];
    if (!found[i]) {
      lanesOut.hit[k] = lanesOut.offsetScale[k] = lanesOut.shades[k] = lanesOut.glossy[k] =
          lanesOut.emitter[k] = lanesOut.object[k] = 0.f;
      for (auto* v : {&lanesOut.p, &lanesOut.ng, &lanesOut.ns, &lanesOut.nsHit, &lanesOut.albedoOverPi,
                      &lanesOut.emitted})
        setLane(*v, k, Vec3(0.f));
      continue;
    }
    const SurfaceMaterial& material = scene.materials[hit.objectId];
    const ShadingPoint sp(scene, ray[i], hit, false);
    lanesOut.hit[k] = 1.f;
    setLane(lanesOut.p, k, hit.p);
    setLane(lanesOut.ng, k, sp.ng);
    setLane(lanesOut.ns, k, sp.ns);
    setLane(lanesOut.nsHit, k, hit.ns);
    lanesOut.offsetScale[k] = hit.offsetScale;
    const bool glossy = !material.bsdf.isDiffuse();
    // directRadiance's two tests of whether anything is reflected.
    lanesOut.shades[k] = (glossy ? material.bsdf.reflects() : !isBlack(material.bsdf.albedo)) ? 1.f : 0.f;
    lanesOut.glossy[k] = glossy ? 1.f : 0.f;
    lanesOut.emitter[k] = material.emits() ? 1.f : 0.f;
    lanesOut.object[k] = float(hit.objectId);
    setLane(lanesOut.albedoOverPi, k, material.bsdf.albedo * kInvPi);
    setLane(lanesOut.emitted, k, emittedAt(scene, material, hit, ray[i]));
  }
}

void queryGlossyLanes(const Scene& scene, const PacketRays& rays, const float (&object)[kMaxPacketLanes],
                      const float (&ns)[3][kMaxPacketLanes], const float (&shaded)[kMaxPacketLanes],
                      int lanes, PacketGlossyLanes& out) {
  static const Bsdf kBlack = makeMicrofacet(Color3(0.f), 1.f, 1.f, 1.f);
  for (int k = 0; k < lanes; ++k) {
    out.material[k] = -1;
    const size_t material = size_t(object[k]);
    const bool glossy = shaded[k] != 0.f && !scene.materials[material].bsdf.isDiffuse();
    const Bsdf& b = glossy ? scene.materials[material].bsdf : kBlack;
    out.conductor[k] = b.type == BsdfType::RoughConductor ? 1.f : 0.f;
    out.ggx[k] =
        b.type == BsdfType::RoughConductor && b.distribution == MicrofacetDistribution::Ggx ? 1.f : 0.f;
    out.alpha[k] = b.alpha;
    out.ks[k] = b.ks;
    out.extIOR[k] = b.extIOR;
    out.intIOR[k] = b.intIOR;
    setLane(out.kd, k, b.albedo);
    setLane(out.R, k, b.specularReflectance);
    if (!glossy) continue;
    // GlossyReflection(bsdf, sp, ray.d) of the ShadingPoint's frame.
    const Frame frame(lane(ns, k));
    out.material[k] = int32_t(material);
    setLane(out.s, k, frame.s);
    setLane(out.t, k, frame.t);
    setLane(out.n, k, frame.n);
    setLane(out.wo, k, frame.toLocal(-lane(rays.d, k)));
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
  // The active lanes' rays, traced together.
  Ray ray[kMaxPacketLanes];
  SurfaceHit hits[kMaxPacketLanes];
  bool found[kMaxPacketLanes];
  int laneOf[kMaxPacketLanes];
  size_t active = 0;
  for (int k = 0; k < lanes; ++k) {
    out.light[k] = -1.f;
    if (rays.active[k] == 0.f) continue;
    ray[active] = segment(rays, k);
    laneOf[active++] = k;
  }
  scene.geometry.intersectMany(ray, active, hits, found, SceneGeometry::Coherence::Incoherent);
  for (size_t i = 0; i < active; ++i) {
    if (!found[i]) continue;
    const int k = laneOf[i];
    const SurfaceHit& hit = hits[i];
    // addEmitterAlong: a sphere light's outer side, a polygon light's emitting side.
    const SurfaceMaterial& material = scene.materials[hit.objectId];
    size_t light;
    Color3 Le;
    if (material.sphereLight >= 0) {
      light = size_t(material.sphereLight);
      Le = scene.sphereLights[light].eval(hit.p, hit.ng, ray[i].d);
    } else if (const PolygonLight* polygon = scene.polygonLightOf(material, hit.primId)) {
      light = scene.sphereLights.size() + size_t(polygon - scene.polygonLights.data());
      Le = polygon->eval(ray[i].d);
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

}  // namespace penumbra
