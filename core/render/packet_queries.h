// The ray queries of the packet kernels in scenes whose geometry the kernels do not hold themselves
// (shapes in a BVH, loose triangles): answered by the scene's SceneGeometry, with the scalar
// integrators' own code around each lane's query (ShadingPoint, emittedAt, SphereLight::eval), so
// that every lane gets exactly what the scalar integrator gets. The kernels keep the shading (light
// sampling, warps, MIS weights, sums) in lanes; the rays go to SceneGeometry's many-ray queries
// together (Embree's streams): a packet's shadow and BSDF-sampled rays, several packets' camera rays.
// Lanes are arrays of kMaxPacketLanes (the first `lanes` used); a lane is active where active[k] != 0.
#pragma once

#include <cstdint>

#include "core/render/packet_kernels.h"

namespace penumbra {

struct Scene;

// What each lane's camera ray hits, as ShadingPoint holds it (normals flipped to the ray's side), with
// what the diffuse shading needs of its material. Lanes that hit nothing are all 0.
struct alignas(64) PacketHitLanes {
  float hit[kMaxPacketLanes];
  float p[3][kMaxPacketLanes], ng[3][kMaxPacketLanes], ns[3][kMaxPacketLanes];
  float nsHit[3][kMaxPacketLanes];  // SurfaceHit::ns, before the ShadingPoint's flip
  float offsetScale[kMaxPacketLanes];
  float shades[kMaxPacketLanes];   // PacketObject::shades
  float glossy[kMaxPacketLanes];   // PacketObject::glossy
  float emitter[kMaxPacketLanes];  // PacketObject::emitter
  float object[kMaxPacketLanes];   // the hit's index in Scene::materials
  float albedoOverPi[3][kMaxPacketLanes];
  float emitted[3][kMaxPacketLanes];  // emittedAt
};

// Rays leaving shading points (tMin 0).
struct alignas(64) PacketSegments {
  float o[3][kMaxPacketLanes], d[3][kMaxPacketLanes];
  float tMax[kMaxPacketLanes];
  float active[kMaxPacketLanes];
};

// What each lane's ray reaches first when that is the front of an area light of non-black radiance
// (addEmitterAlong): the light's index among the area lights (Scene::sphereLights, then
// Scene::polygonLights; -1 otherwise, and in inactive lanes), the radiance it sends back along the ray,
// and the hit's point and outward normal.
struct alignas(64) PacketEmitterLanes {
  float light[kMaxPacketLanes];
  float Le[3][kMaxPacketLanes];
  float p[3][kMaxPacketLanes], ng[3][kMaxPacketLanes];
};

// The shading points of a packet's lanes as the kernels hold them (ShadingPoint::facing), active where
// a lane is shaded.
struct alignas(64) PacketShadingLanes {
  float p[3][kMaxPacketLanes], ng[3][kMaxPacketLanes], ns[3][kMaxPacketLanes];
  float offsetScale[kMaxPacketLanes];
  float active[kMaxPacketLanes];
};

// Radiance per lane.
struct alignas(64) PacketColorLanes {
  float c[3][kMaxPacketLanes];
};

// The glossy surfaces of a packet's shaded lanes as GlossyReflection holds them: the material, the
// shading frame (Frame of the facing shading normal) and wo, the direction to the camera in that frame,
// and the material's Bsdf fields the lanes evaluate it with (flags 1 or 0). A lane is glossy where
// material[k] >= 0; the other lanes hold a black microfacet BSDF.
struct alignas(64) PacketGlossyLanes {
  int32_t material[kMaxPacketLanes];
  float s[3][kMaxPacketLanes], t[3][kMaxPacketLanes], n[3][kMaxPacketLanes];
  float wo[3][kMaxPacketLanes];
  float conductor[kMaxPacketLanes];  // roughconductor (else microfacet)
  float ggx[kMaxPacketLanes];        // a GGX roughconductor (else Beckmann)
  float alpha[kMaxPacketLanes], ks[kMaxPacketLanes], extIOR[kMaxPacketLanes], intIOR[kMaxPacketLanes];
  float kd[3][kMaxPacketLanes];  // Bsdf::albedo
  float R[3][kMaxPacketLanes];   // Bsdf::specularReflectance
};

// Camera rays queried together: several packets' worth, since Embree traverses a coherent stream of
// 4 or 8 rays hardly faster than one ray at a time (32 measured faster than 16 and 64 on the Cornell
// box with AVX2 and AVX-512).
inline constexpr int kQueriedCameraRays = 32;
// The hits of `packets` packets' camera rays (rays[0 .. packets − 1], `lanes` lanes each), queried
// together as one stream; packets × lanes is at most kQueriedCameraRays.
void queryCameraHits(const Scene& scene, const PacketRays* rays, int packets, int lanes, PacketHitLanes* out);
// The glossy lanes among those of `shaded` (nonzero) whose hit is `object` (PacketHitLanes::object):
// their frames about the facing shading normals ns and the camera rays' wo.
void queryGlossyLanes(const Scene& scene, const PacketRays& rays, const float (&object)[kMaxPacketLanes],
                      const float (&ns)[3][kMaxPacketLanes], const float (&shaded)[kMaxPacketLanes],
                      int lanes, PacketGlossyLanes& out);
// SceneGeometry::occluded(ray, skipSphere) of each active lane's segment: blocked[k] is 1 or 0.
void queryOccluded(const Scene& scene, const PacketSegments& rays, int lanes, int32_t skipSphere,
                   float* blocked);
void queryEmittersAlong(const Scene& scene, const PacketSegments& rays, int lanes, PacketEmitterLanes& out);
// MisIntegrator::lightPdf, by the technique of `measure`, of each active lane's direction w reaching area
// light light[k] (spheres, then polygons) at p with normal n, from the lane's shading point.
void queryLightPdfs(const Scene& scene, LightMeasure measure, const PacketShadingLanes& points,
                    const float (&light)[kMaxPacketLanes], const float (&w)[3][kMaxPacketLanes],
                    const float (&p)[3][kMaxPacketLanes], const float (&n)[3][kMaxPacketLanes], int lanes,
                    float* pdf);
// LightTechnique<measure, Light>'s samples of area light light[k] (spheres, then polygons; none where
// negative) from draws firstDraw .. firstDraw + count − 1 of `draws` at each active lane's shading point,
// out[i] for draw firstDraw + i: the direction, distance and pdf of the sample, and for the projected
// solid angle `projected`, its cosOverPdf (Ω⊥ as the technique rounds it). pdf is 0 where the light
// cannot be sampled or the sample is not valid, and in inactive lanes.
struct alignas(64) PacketLightSampleLanes {
  float wi[3][kMaxPacketLanes];
  float dist[kMaxPacketLanes], pdf[kMaxPacketLanes], projected[kMaxPacketLanes];
};
void queryLightSamples(const Scene& scene, LightMeasure measure, const float (&light)[kMaxPacketLanes],
                       const PacketShadingLanes& points, const PacketDraws& draws, size_t firstDraw,
                       int count, int lanes, PacketLightSampleLanes* out);

}  // namespace penumbra
