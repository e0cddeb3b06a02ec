#include "core/render/packet_queries.h"

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

}  // namespace

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
    const int32_t light = scene.materials[hit.objectId].sphereLight;
    if (light < 0) continue;
    const Color3 Le = scene.sphereLights[size_t(light)].eval(hit.p, hit.ng, ray.d);
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
