// The packet kernels, compiled by Highway once per instruction set (this file includes itself through
// hwy/foreach_target.h) and chosen at run time by the CPU's features (at the end of this file; not by
// Highway's HWY_DYNAMIC_DISPATCH, whose library libhwy.so calibrates a timer with RDTSCP when it is
// loaded, an instruction valgrind cannot run, and valgrind is how this project counts instructions). Each
// function mirrors, lane by lane, the scalar function its comment names: the same float and double operations
// in the same order, branches as masks. The file is compiled without floating-point contraction, so no
// multiply-add is fused where the scalar code rounds twice.

#include <cpuid.h>

#include <atomic>
#include <cstring>
#include <string>
#include <vector>

#include "core/geometry/parallelogram.h"
#include "core/lights/sphere_light.h"
#include "core/math/float_util.h"
#include "core/math/sincos_turns.h"
#include "core/math/vec.h"
#include "core/render/packet_kernels.h"

// SSSE3 and AVX3_DL add nothing these kernels use over SSE4 and AVX3; not compiling them saves build
// time.
#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SSSE3 | HWY_AVX3_DL)
#endif

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "core/render/packet_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "core/render/packet_bsdf-inl.h"
#include "core/render/packet_camera-inl.h"
#include "core/render/packet_film-inl.h"
#include "core/render/packet_geometry-inl.h"
#include "core/render/packet_light_bvh-inl.h"
#include "core/render/packet_light_table-inl.h"
#include "core/render/packet_lights-inl.h"
#include "core/render/packet_math-inl.h"
#include "core/render/packet_polygon_techniques-inl.h"
#include "core/render/packet_sampler-inl.h"
#include "core/render/packet_sphere_techniques-inl.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace {

namespace hn = hwy::HWY_NAMESPACE;

// E += Le · factor in the lanes of m (E unchanged elsewhere).
HWY_INLINE void addRadiance(MF m, const V3F& Le, VF factor, V3F& E) {
  E = select(m, V3F{E.x + Le.x * factor, E.y + Le.y * factor, E.z + Le.z * factor}, E);
}

// deltaIrradiance (direct_lighting.h): each point and directional light traced once, reflection(Li, wi)
// cos θ where it reaches the shaded lanes.
HWY_INLINE V3F deltaIrradiance(const PacketScene& scene, const PacketHit& h, MF shaded,
                               const GlossySurfaces& g) {
  const DF df;
  const VF zero = hn::Zero(df);
  V3F E{zero, zero, zero};
  for (const PacketPointLight& light : scene.pointLights) {
    // PointLight::sample: Li = I / d² towards the light (none from the light's own position).
    const V3F toL{setF(light.position[0]) - h.p.x, setF(light.position[1]) - h.p.y,
                  setF(light.position[2]) - h.p.z};
    const VF d2 = dot(toL, toL);
    const VF dist = hn::Sqrt(d2);
    const V3F wi{toL.x / dist, toL.y / dist, toL.z / dist};
    const V3F Li{setF(light.intensity[0]) / d2, setF(light.intensity[1]) / d2, setF(light.intensity[2]) / d2};
    const MF valid = hn::And(d2 > zero, d2 < setF(INFINITY));
    const MF black = hn::And(hn::And(Li.x == zero, Li.y == zero), Li.z == zero);
    const VF cosTheta = dot(h.ns, wi);
    MF lit =
        hn::AndNot(black, hn::And(hn::And(shaded, valid), hn::And(cosTheta > zero, dot(wi, h.ng) > zero)));
    if (hn::AllFalse(df, lit)) continue;
    // ShadingPoint::spawnShadowRayToPoint: direction and length from the offset origin.
    const V3F target = setF3(light.position);
    const V3F origin = offsetRayOrigin(h.p, h.ng, h.offsetScale, toL);
    const V3F toTarget{target.x - origin.x, target.y - origin.y, target.z - origin.z};
    const VF length = hn::Sqrt(dot(toTarget, toTarget));
    const VF inv = setF(1.f) / length;
    const V3F w = scaled(toTarget, inv);
    const VF tMax = length - setF(2.f * kRayOffsetScale) * maxOf(setF(light.scale), h.offsetScale);
    lit = hn::AndNot(occluded(scene, origin, w, tMax, -1, lit), lit);
    if (hn::AllFalse(df, lit)) continue;
    addRadiance(lit, reflected(g, lit, Li, wi), cosTheta, E);
  }
  for (const PacketDirectionalLight& light : scene.directionalLights) {
    if (light.black) continue;
    const V3F wi = setF3(light.direction);
    const VF cosTheta = dot(h.ns, wi);
    MF lit = hn::And(shaded, hn::And(cosTheta > zero, dot(wi, h.ng) > zero));
    if (hn::AllFalse(df, lit)) continue;
    const V3F origin = offsetRayOrigin(h.p, h.ng, h.offsetScale, wi);
    lit = hn::AndNot(occluded(scene, origin, wi, setF(scene.rayLengthBound), -1, lit), lit);
    if (hn::AllFalse(df, lit)) continue;
    addRadiance(lit, reflected(g, lit, setF3(light.irradiance), wi), cosTheta, E);
  }
  return E;
}

// directRadiance's result: the emission at the hit, plus where shaded on a diffuse surface albedo/π times
// (the delta lights' irradiance plus the strategy's estimate), on a glossy one the delta lights' and the
// estimate's reflected radiance.
HWY_INLINE void storeRadiance(const PacketScene& scene, MF shaded, const PacketHit& h,
                              const GlossySurfaces& g, const V3F& area, PacketRadiance& out) {
  const V3F delta = deltaIrradiance(scene, h, shaded, g);
  const V3F E{delta.x + area.x, delta.y + area.y, delta.z + area.z};
  V3F L{h.emitted.x + h.albedoOverPi.x * E.x, h.emitted.y + h.albedoOverPi.y * E.y,
        h.emitted.z + h.albedoOverPi.z * E.z};
  if (g.any)
    L = select(g.lanes,
               V3F{(h.emitted.x + delta.x) + area.x, (h.emitted.y + delta.y) + area.y,
                   (h.emitted.z + delta.z) + area.z},
               L);
  storeF3(select(shaded, L, h.emitted), out.L);
}

// luminance (vec.h).
HWY_INLINE VF luminance(const V3F& c) {
  return setF(0.212671f) * c.x + setF(0.715160f) * c.y + setF(0.072169f) * c.z;
}

// MisLightShareIntegrator's channels from the techniques' estimates: per shaded lane the luminance of
// the light technique's part (R), of the surface's (G) and of the rest (B: the emission and the delta
// lights), each part times albedo/π on a diffuse surface; on an emitter the whole estimate in B; the
// emission's luminance in B elsewhere.
HWY_INLINE void storeLightShare(const PacketScene& scene, MF shaded, const PacketHit& h,
                                const GlossySurfaces& g, const V3F& lightPart, const V3F& bsdfPart,
                                PacketRadiance& out) {
  const DF df;
  const VF one = setF(1.f);
  const V3F delta = deltaIrradiance(scene, h, shaded, g);
  const V3F scale = g.any ? select(g.lanes, V3F{one, one, one}, h.albedoOverPi) : h.albedoOverPi;
  const V3F L = h.emitted;
  const V3F whole =
      times(scale, V3F{delta.x + (lightPart.x + bsdfPart.x), delta.y + (lightPart.y + bsdfPart.y),
                       delta.z + (lightPart.z + bsdfPart.z)});
  const V3F rest = times(scale, delta);
  const MF emitter = hn::And(shaded, h.emitter), shares = hn::AndNot(h.emitter, shaded);
  const VF R = hn::IfThenElseZero(shares, luminance(times(scale, lightPart)));
  const VF G = hn::IfThenElseZero(shares, luminance(times(scale, bsdfPart)));
  VF B = luminance(L);
  B = hn::IfThenElse(shares, luminance(V3F{L.x + rest.x, L.y + rest.y, L.z + rest.z}), B);
  B = hn::IfThenElse(emitter, luminance(V3F{L.x + whole.x, L.y + whole.y, L.z + whole.z}), B);
  hn::StoreU(R, df, out.L[0]);
  hn::StoreU(G, df, out.L[1]);
  hn::StoreU(B, df, out.L[2]);
}

// SimpleIntegrator: the delta lights alone.
HWY_INLINE void shadeSimple(const PacketScene& scene, const PacketRays& rays, const PacketHitLanes* queried,
                            PacketRadiance& out) {
  const DF df;
  const PacketHit h = cameraHit(scene, rays, queried);
  const VF zero = hn::Zero(df);
  const MF shaded = hn::And(h.hit, h.shades);
  GlossySurfaces g;
  findGlossy(scene, rays, h, shaded, g);
  storeRadiance(scene, shaded, h, g, V3F{zero, zero, zero}, out);
}

// The rest of unoccludedLightSample once sample s is drawn: the lanes of m it lights (a valid sample
// above the surface, leavesSurface, whose shadow ray ShadingPoint::spawnShadowRayAlong is not blocked),
// with its cos θ. lightScale is lightScaleOf; the shadow rays skip sphere skipSphere (-1: none).
HWY_INLINE MF reachesLight(const PacketScene& scene, const PacketHit& h, MF m, const PacketLightSample& s,
                           VF lightScale, int32_t skipSphere, VF& cosTheta) {
  const DF df;
  const VF zero = hn::Zero(df);
  cosTheta = dot(h.ns, s.wi);
  const MF lit = hn::And(hn::And(m, s.valid), hn::And(cosTheta > zero, dot(s.wi, h.ng) > zero));
  if (hn::AllFalse(df, lit)) return lit;
  const V3F origin = offsetRayOrigin(h.p, h.ng, h.offsetScale, s.wi);
  const VF tMax =
      s.dist - setF(kRayOffsetScale) * (setF(2.f) * maxOf(lightScale, h.offsetScale) + h.offsetScale);
  return hn::AndNot(occluded(scene, origin, s.wi, tMax, skipSphere, lit), lit);
}

// Light-sampling draw j of `technique` in the lanes of m, towards lights of radiance Le whose shadow rays
// stop lightScale-relative short of them and skip sphere skipSphere (-1: none): E += reflection(Le, wi)
// · factor(s, cos θ, the glossy lanes' BSDF density of wi) where it lights. The density is computed only
// with kGlossyPdf (0 otherwise).
template <bool kGlossyPdf = false, class Technique, class Factor>
HWY_INLINE void addLightDraw(const PacketScene& scene, const Technique& technique, VF lightScale,
                             int32_t skipSphere, const V3F& Le, const PacketHit& h, const GlossySurfaces& g,
                             MF m, const PacketDraws& draws, size_t j, const Factor& factor, V3F& E) {
  VF cosTheta;
  const PacketLightSample s = technique.sample(draws, j);
  const MF lit = reachesLight(scene, h, m, s, lightScale, skipSphere, cosTheta);
  if (hn::AllFalse(DF(), lit)) return;
  VF glossyPdf;
  const V3F reflectedLe = reflected(g, lit, Le, s.wi, kGlossyPdf ? &glossyPdf : nullptr);
  addRadiance(lit, reflectedLe, factor(s, cosTheta, kGlossyPdf ? glossyPdf : hn::Zero(DF())), E);
}

// Draw j of sphere light `light` by `technique` (addLightDraw).
template <LightMeasure kMeasure, bool kGlossyPdf = false, class Factor>
HWY_INLINE void addLightSample(const PacketScene& scene, const PacketLight& light,
                               const SphereTechnique<kMeasure>& technique, const PacketHit& h,
                               const GlossySurfaces& g, MF m, const PacketDraws& draws, size_t j,
                               const Factor& factor, V3F& E) {
  addLightDraw<kGlossyPdf>(scene, technique, setF(light.scale), light.geometrySphere, setF3(light.radiance),
                           h, g, m, draws, j, factor, E);
}

// Draw j of each lane's polygon light by `technique` (addLightDraw).
template <LightMeasure kMeasure, bool kGlossyPdf = false, class Factor>
HWY_INLINE void addPolygonSample(const PacketScene& scene, const PolygonTechnique<kMeasure>& technique,
                                 const PacketHit& h, const GlossySurfaces& g, MF m, const PacketDraws& draws,
                                 size_t j, const Factor& factor, V3F& E) {
  addLightDraw<kGlossyPdf>(scene, technique, technique.light.scale, -1, technique.light.radiance, h, g, m,
                           draws, j, factor, E);
}

// everyLightIrradiance's sum (before the mean) in the shaded lanes: `samples` draws of each area light
// (spheres, then polygons) by the measure, each term reflection(Le, wi) · factor(s, cos θ, glossy density;
// computed only with kGlossyPdf).
template <LightMeasure kMeasure, bool kGlossyPdf, class Factor>
HWY_INLINE void addEveryLight(const PacketScene& scene, const PacketHit& h, const GlossySurfaces& g,
                              MF shaded, const PacketDraws& draws, int samples, const Factor& factor,
                              V3F& E) {
  const size_t spheres = scene.lights.size(), perLight = size_t(samples);
  for (size_t l = 0; l < spheres; ++l) {
    const PacketLight& light = scene.lights[l];
    if (!sampled(light)) continue;
    const SphereTechnique<kMeasure> technique(scene, l, h, shaded, (l + 1) * perLight);
    for (size_t i = 0; i < perLight; ++i)
      addLightSample<kMeasure, kGlossyPdf>(scene, light, technique, h, g, shaded, draws, l * perLight + i,
                                           factor, E);
  }
  for (size_t l = 0; l < scene.polygons.size(); ++l) {
    if (scene.polygons[l].skipped) continue;
    const PolygonLanes light = broadcast(scene.polygons[l]);
    const size_t first = (spheres + l) * perLight;
    const PolygonTechnique<kMeasure> technique(scene, light, broadcastIndex(spheres + l).data(), h, shaded,
                                               first + perLight);
    for (size_t i = 0; i < perLight; ++i)
      addPolygonSample<kMeasure, kGlossyPdf>(scene, technique, h, g, shaded, draws, first + i, factor, E);
  }
}

// LightDirectIntegrator<measure, All> through directRadiance: every light, every sample, shadow
// tested; the mean over the samples, times albedo/π, plus the emission at the hit.
template <LightMeasure kMeasure>
HWY_INLINE void shadeDirect(const PacketScene& scene, const PacketRays& rays, const PacketHitLanes* queried,
                            const PacketDraws& draws, PacketRadiance& out) {
  const DF df;
  const PacketHit h = cameraHit(scene, rays, queried);
  const VF zero = hn::Zero(df);
  V3F E{zero, zero, zero};
  const MF shaded = hn::And(h.hit, h.shades);
  GlossySurfaces g;
  findGlossy(scene, rays, h, shaded, g);
  if (!hn::AllFalse(df, shaded)) {
    const int samples = scene.samples;
    const auto factor = [](const PacketLightSample& s, VF cosTheta, VF) {
      return cosOverPdf<kMeasure>(s, cosTheta);
    };
    addEveryLight<kMeasure, false>(scene, h, g, shaded, draws, samples, factor, E);
    const VF invSamples = setF(1.f / float(samples));
    // directRadiance: L + albedo/π · (delta lights' 0 + the estimate).
    E = scaled(E, invSamples);
  }
  storeRadiance(scene, shaded, h, g, E, out);
}

// The light each shaded lane picks (LightDirectIntegrator::selectedLightIrradiance): its index among
// the area lights (-1 where nothing is picked, and in lanes not shaded) and the probability it was picked
// with (0 there).
struct alignas(64) LightPicks {
  float light[kMaxPacketLanes];
  double pmf[kMaxPacketLanes];
};

// The light each shaded lane picks for sample i from its pick draw j, in lanes: by the light BVH's walk
// or by the uniform or power selection's alias table.
HWY_INLINE void pickLights(const PacketScene& scene, const PacketHit& h, MF shaded, const PacketDraws& draws,
                           size_t j, LightPicks& picks) {
  VF u0, u1;
  loadDraw(draws, j, u0, u1);
  if (scene.selection == LightSelection::Bvh)
    return pickBvhLights(scene.lightBvh, h.p, h.ns, u0, u1, shaded, picks.light, picks.pmf);
  pickTableLights(scene.lightTable, u0, u1, shaded, picks.light, picks.pmf);
}

// LightDirectIntegrator<measure, selection> through directRadiance (selectedLightIrradiance): per
// sample one light picked per lane, sampled by the measure in the lanes that picked it, each sample's
// cos θ / (pdf · pmf) divided in double.
template <LightMeasure kMeasure>
HWY_INLINE void shadeSelected(const PacketScene& scene, const PacketRays& rays, const PacketHitLanes* queried,
                              const PacketDraws& draws, PacketRadiance& out) {
  const DF df;
  const DD dd;
  const PacketHit h = cameraHit(scene, rays, queried);
  const VF zero = hn::Zero(df);
  V3F E{zero, zero, zero};
  const MF shaded = hn::And(h.hit, h.shades);
  GlossySurfaces g;
  findGlossy(scene, rays, h, shaded, g);
  if (!hn::AllFalse(df, shaded)) {
    const size_t lanes = hn::Lanes(df);
    for (int i = 0; i < scene.samples; ++i) {
      const size_t pickDraw = 2 * size_t(i), lightDraw = pickDraw + 1;
      LightPicks picks;
      pickLights(scene, h, shaded, draws, pickDraw, picks);
      const VF picked = hn::LoadU(df, picks.light);
      const VD pmf = hn::LoadU(dd, picks.pmf);
      const auto selectedFactor = [&](const PacketLightSample& s, VF cosTheta, VF) {
        return cosOverSelectedPdf<kMeasure>(s, cosTheta, pmf);
      };
      if (!scene.polygons.empty()) {
        // Every lane that picked a polygon light, each sampling its own.
        const float spheres = float(scene.lights.size());
        alignas(64) float polygon[kMaxPacketLanes];
        for (size_t k = 0; k < lanes; ++k) {
          const float l = picks.light[k];
          const bool lights = l >= spheres && !scene.polygons[size_t(l - spheres)].skipped;
          polygon[k] = lights ? l - spheres : -1.f;
        }
        const MF pickedPolygon = hn::And(shaded, hn::Load(df, polygon) >= hn::Zero(df));
        if (!hn::AllFalse(df, pickedPolygon)) {
          const PolygonLanes light = gatherPolygons(scene.polygons, polygon);
          addPolygonSample(
              scene, PolygonTechnique<kMeasure>(scene, light, picks.light, h, pickedPolygon, lightDraw + 1),
              h, g, pickedPolygon, draws, lightDraw, selectedFactor, E);
        }
      }
      // Each light some lane picked, once (lanes picking one light are handled together).
      for (size_t k = 0; k < lanes; ++k) {
        const float l = picks.light[k];
        if (l < 0.f || size_t(l) >= scene.lights.size()) continue;
        bool seen = false;
        for (size_t e = 0; e < k && !seen; ++e) seen = picks.light[e] == l;
        if (seen) continue;
        const PacketLight& light = scene.lights[size_t(l)];
        if (!sampled(light)) continue;
        const MF lanesOfLight = hn::And(shaded, picked == setF(l));
        addLightSample<kMeasure>(scene, light,
                                 SphereTechnique<kMeasure>(scene, size_t(l), h, lanesOfLight, lightDraw + 1),
                                 h, g, lanesOfLight, draws, lightDraw, selectedFactor, E);
      }
    }
    const VF invSamples = setF(1.f / float(scene.samples));
    E = scaled(E, invSamples);
  }
  storeRadiance(scene, shaded, h, g, E, out);
}

// HemisphereDirectIntegrator<kWarp> through directRadiance, and with kBsdf BsdfDirectIntegrator (the
// cosine warp on diffuse surfaces, the BSDF's sampler on glossy ones): directions about the shading
// normal, each traced to the emitter it reaches first.
template <HemisphereWarp kWarp, bool kBsdf = false>
HWY_INLINE void shadeHemisphere(const PacketScene& scene, const PacketRays& rays,
                                const PacketHitLanes* queried, const PacketDraws& draws,
                                PacketRadiance& out) {
  static_assert(!kBsdf || kWarp == HemisphereWarp::Cosine);
  const DF df;
  const PacketHit h = cameraHit(scene, rays, queried);
  const VF zero = hn::Zero(df);
  V3F E{zero, zero, zero};
  const MF shaded = hn::And(h.hit, h.shades);
  GlossySurfaces g;
  findGlossy(scene, rays, h, shaded, g);
  // Scene::hasAreaLights.
  if (!hn::AllFalse(df, shaded) && (!scene.lights.empty() || !scene.polygons.empty())) {
    const FrameF frame = frameAbout(h.ns);
    const int samples = scene.samples;
    const bool bsdfSampled = kBsdf && g.any;
    for (int i = 0; i < samples; ++i) {
      const SurfaceDirection d = surfaceDirection<kWarp>(g, bsdfSampled, frame, draws, size_t(i));
      // leavesSurface(sp, w, cos θ).
      const MF active = hn::And(shaded, hn::And(d.valid, dot(d.w, h.ng) > zero));
      if (hn::AllFalse(df, active)) continue;
      forEachEmitterAlong(scene, offsetRayOrigin(h.p, h.ng, h.offsetScale, d.w), d.w, active,
                          [&](size_t, MF lanes, const V3F& Le, const V3F&, const V3F&, VF) {
                            // The BSDF's samples carry f cos θ / pdf; f of the warps' is evaluated.
                            const V3F reflectedLe =
                                bsdfSampled ? times(Le, d.weight) : reflected(g, lanes, Le, d.w);
                            addRadiance(lanes, reflectedLe, d.cosOverPdf, E);
                          });
    }
    const VF invSamples = setF(1.f / float(samples));
    E = scaled(E, invSamples);
  }
  storeRadiance(scene, shaded, h, g, E, out);
}

// misWeight (mis_weight.h): 1 / (1 + r), r = b / a (squared for the power heuristic).
template <MisHeuristic kHeuristic>
HWY_INLINE VF misWeight(VF a, VF b) {
  const VF r = b / a;
  const VF one = setF(1.f);
  return kHeuristic == MisHeuristic::Balance ? one / (one + r) : one / (one + r * r);
}

// MisIntegrator<measure, heuristic> through directRadiance: every light sampled by the measure and the
// surface's own directions (the cosine hemisphere on diffuse lanes, the BSDF's sampler on glossy ones),
// each sample weighted by the heuristic of the two densities. Light samples and light densities the
// lanes cannot compute exactly (PolygonTechnique's and SphereTechnique's scalar lanes) come from the
// scalar techniques lane by lane (ScalarLightSamples, queryLightPdfs).
// With PacketScene::lightShare, MisLightShareIntegrator's channels instead of the radiance.
template <LightMeasure kMeasure, MisHeuristic kHeuristic>
HWY_INLINE void shadeMis(const PacketScene& scene, const PacketRays& rays, const PacketHitLanes* queried,
                         const PacketDraws& draws, PacketRadiance& out) {
  const DF df;
  const PacketHit h = cameraHit(scene, rays, queried);
  const VF zero = hn::Zero(df);
  // The two techniques' weighted estimates (MisIntegrator::techniques).
  V3F lightPart{zero, zero, zero}, bsdfPart{zero, zero, zero};
  const MF shaded = hn::And(h.hit, h.shades);
  GlossySurfaces g;
  findGlossy(scene, rays, h, shaded, g);
  // Scene::hasAreaLights.
  if (!hn::AllFalse(df, shaded) && (!scene.lights.empty() || !scene.polygons.empty())) {
    const int nLight = scene.lightSamples, nBsdf = scene.bsdfSamples;
    const VF nL = setF(float(nLight)), nB = setF(float(nBsdf));
    const size_t spheres = scene.lights.size();
    if (nLight > 0) {
      const auto misFactor = [&](const PacketLightSample& s, VF cosTheta, VF glossyPdf) {
        // Reflection::pdf: the cosine hemisphere's on diffuse lanes, the BSDF's on glossy ones.
        const VF surfacePdf = hn::IfThenElse(g.lanes, glossyPdf, cosTheta * setF(kInvPi));
        const VF weight = misWeight<kHeuristic>(nL * s.pdf, nB * surfacePdf);
        return cosOverPdf<kMeasure>(s, cosTheta) * weight;
      };
      addEveryLight<kMeasure, true>(scene, h, g, shaded, draws, nLight, misFactor, lightPart);
      const VF inv = setF(1.f / float(nLight));
      lightPart = scaled(lightPart, inv);
    }
    if (nBsdf > 0) {
      const FrameF frame = frameAbout(h.ns);
      const size_t firstDraw = (spheres + scene.polygons.size()) * size_t(nLight);
      for (int i = 0; i < nBsdf; ++i) {
        const SurfaceDirection d =
            surfaceDirection<HemisphereWarp::Cosine>(g, g.any, frame, draws, firstDraw + size_t(i));
        const V3F w = d.w;
        const MF active = hn::And(shaded, hn::And(d.valid, dot(w, h.ng) > zero));
        if (hn::AllFalse(df, active)) continue;
        forEachEmitterAlong(
            scene, offsetRayOrigin(h.p, h.ng, h.offsetScale, w), w, active,
            [&](size_t l, MF lanes, const V3F& Le, const V3F& p, const V3F& n, VF lightIndex) {
              // MisIntegrator::lightPdf of the light reached: in lanes, or lane by lane.
              VF pL = zero;
              if (nLight > 0 && l < spheres) {
                if (scene.lights[l].radius > 0.f)
                  pL = SphereTechnique<kMeasure>(scene, l, h, lanes, 0).pdf(w, p, n);
              } else if (nLight > 0) {
                // Each lane's polygon light, its technique set up at the lane's shading point.
                HWY_ALIGN float index[kMaxPacketLanes], polygon[kMaxPacketLanes];
                hn::Store(lightIndex, df, index);
                hn::Store(hn::IfThenElse(lanes, lightIndex - setF(float(spheres)), setF(-1.f)), df, polygon);
                const PolygonLanes light = gatherPolygons(scene.polygons, polygon);
                pL = PolygonTechnique<kMeasure>(scene, light, index, h, lanes, 0).pdf(w, p, n);
              }
              const VF weight = misWeight<kHeuristic>(nB * d.pdf, nL * pL);
              addRadiance(lanes, times(Le, d.weight), d.cosOverPdf * weight, bsdfPart);
            });
      }
      const VF inv = setF(1.f / float(nBsdf));
      bsdfPart = scaled(bsdfPart, inv);
    }
  }
  if (scene.lightShare) return storeLightShare(scene, shaded, h, g, lightPart, bsdfPart, out);
  storeRadiance(scene, shaded, h, g,
                V3F{lightPart.x + bsdfPart.x, lightPart.y + bsdfPart.y, lightPart.z + bsdfPart.z}, out);
}

// AoIntegrator<kWarp>: hemisphere directions about the shading normal, each tested for occlusion up
// to the scene's extent; the unoccluded ones' contributions (1 for the cosine warp, 2 cos θ for the
// uniform one) summed in order.
template <HemisphereWarp kWarp>
HWY_INLINE void shadeAo(const PacketScene& scene, const PacketRays& rays, const PacketHitLanes* queried,
                        const PacketDraws& draws, PacketRadiance& out) {
  const DF df;
  const PacketHit h = cameraHit(scene, rays, queried);
  const VF zero = hn::Zero(df);
  VF sum = zero;
  if (!hn::AllFalse(df, h.hit)) {
    const FrameF frame = frameAbout(h.ns);
    const VF tMax = setF(scene.rayLengthBound);
    for (int i = 0; i < scene.samples; ++i) {
      VF u0, u1;
      loadDraw(draws, i, u0, u1);
      const V3F local = hemisphereDirection<kWarp>(u0, u1);
      const V3F w = toWorld(frame, local);
      // Below the true surface: blocked by it (a NaN direction is traced, as there).
      MF active = hn::AndNot(dot(w, h.ng) <= zero, h.hit);
      if (hn::AllFalse(df, active)) continue;
      const VF contribution = kWarp == HemisphereWarp::Cosine ? setF(1.f) : setF(2.f) * local.z;
      active = hn::AndNot(occluded(scene, offsetRayOrigin(h.p, h.ng, h.offsetScale, w), w, tMax, -1, active),
                          active);
      sum = hn::IfThenElse(active, sum + contribution, sum);
    }
  }
  const VF L = sum * setF(1.f / float(scene.samples));
  hn::StoreU(L, df, out.L[0]);
  hn::StoreU(L, df, out.L[1]);
  hn::StoreU(L, df, out.L[2]);
}

// NormalsIntegrator: |ns| of the hit as it comes from the geometry, 0 where nothing is hit.
HWY_INLINE void shadeNormals(const PacketScene& scene, const PacketRays& rays, const PacketHitLanes* queried,
                             PacketRadiance& out) {
  const DF df;
  const PacketHit h = cameraHit(scene, rays, queried);
  hn::StoreU(hn::IfThenElseZero(h.hit, hn::Abs(h.nsHit.x)), df, out.L[0]);
  hn::StoreU(hn::IfThenElseZero(h.hit, hn::Abs(h.nsHit.y)), df, out.L[1]);
  hn::StoreU(hn::IfThenElseZero(h.hit, hn::Abs(h.nsHit.z)), df, out.L[2]);
}

}  // namespace

void ShadePacket(const PacketScene& scene, const PacketRays& rays, const PacketHitLanes* queried,
                 const PacketDraws& draws, PacketRadiance& out) {
  switch (scene.kernel) {
    case PacketKernel::LightArea:
      return shadeDirect<LightMeasure::Area>(scene, rays, queried, draws, out);
    case PacketKernel::LightSolidAngle:
      return shadeDirect<LightMeasure::SolidAngle>(scene, rays, queried, draws, out);
    case PacketKernel::LightAreaSelected:
      return shadeSelected<LightMeasure::Area>(scene, rays, queried, draws, out);
    case PacketKernel::LightSolidAngleSelected:
      return shadeSelected<LightMeasure::SolidAngle>(scene, rays, queried, draws, out);
    case PacketKernel::LightProjectedSolidAngle:
      return shadeDirect<LightMeasure::ProjectedSolidAngle>(scene, rays, queried, draws, out);
    case PacketKernel::LightProjectedSolidAngleSelected:
      return shadeSelected<LightMeasure::ProjectedSolidAngle>(scene, rays, queried, draws, out);
    case PacketKernel::HemisphereUniform:
      return shadeHemisphere<HemisphereWarp::Uniform>(scene, rays, queried, draws, out);
    case PacketKernel::HemisphereCosine:
      return shadeHemisphere<HemisphereWarp::Cosine>(scene, rays, queried, draws, out);
    case PacketKernel::Bsdf:
      return shadeHemisphere<HemisphereWarp::Cosine, true>(scene, rays, queried, draws, out);
    case PacketKernel::MisAreaBalance:
      return shadeMis<LightMeasure::Area, MisHeuristic::Balance>(scene, rays, queried, draws, out);
    case PacketKernel::MisAreaPower:
      return shadeMis<LightMeasure::Area, MisHeuristic::Power>(scene, rays, queried, draws, out);
    case PacketKernel::MisSolidAngleBalance:
      return shadeMis<LightMeasure::SolidAngle, MisHeuristic::Balance>(scene, rays, queried, draws, out);
    case PacketKernel::MisSolidAnglePower:
      return shadeMis<LightMeasure::SolidAngle, MisHeuristic::Power>(scene, rays, queried, draws, out);
    case PacketKernel::MisProjectedSolidAngleBalance:
      return shadeMis<LightMeasure::ProjectedSolidAngle, MisHeuristic::Balance>(scene, rays, queried, draws,
                                                                                out);
    case PacketKernel::MisProjectedSolidAnglePower:
      return shadeMis<LightMeasure::ProjectedSolidAngle, MisHeuristic::Power>(scene, rays, queried, draws,
                                                                              out);
    case PacketKernel::Simple:
      return shadeSimple(scene, rays, queried, out);
    case PacketKernel::AoUniform:
      return shadeAo<HemisphereWarp::Uniform>(scene, rays, queried, draws, out);
    case PacketKernel::AoCosine:
      return shadeAo<HemisphereWarp::Cosine>(scene, rays, queried, draws, out);
    case PacketKernel::Normals:
      return shadeNormals(scene, rays, queried, out);
  }
}
void CameraRays(const PacketCamera& camera, int x0, int y, int count, const float (&u)[2][kMaxPacketLanes],
                PacketRays& rays, float (&weight)[kMaxPacketLanes]) {
  cameraRays(camera, x0, y, count, u, rays, weight);
}
void SamplerDraws(const PacketStreamStart& start, const PacketDrawPlan& plan, float (&u)[2][kMaxPacketLanes],
                  PacketDraws& draws) {
  samplerDraws(start, plan, u, draws);
}
uint32_t FilmAdd(const PacketRadiance& radiance, const float (&weight)[kMaxPacketLanes], int count,
                 double* sums) {
  return filmAdd(radiance, weight, count, sums);
}
int Lanes() {
  return static_cast<int>(hn::Lanes(DD()));
}

}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

// The entries that let the tests run one piece of a kernel alone.
#include "core/render/packet_test_entries-inl.h"

#if HWY_ONCE
namespace penumbra {
namespace {

// One instruction set's kernels.
struct PacketTarget {
  int64_t target;  // Highway's bit for it
  PacketKernels kernels;
  int (*lanes)();
};

// One compiled set's entry: its bit, its kernels, its lane count.
#define PENUMBRA_PACKET_TARGET(bit, ns)                                                            \
  {                                                                                                \
    bit, {&ns::ShadePacket, &ns::CameraRays,        &ns::SamplerDraws,     &ns::FilmAdd,           \
          &ns::TablePicks,  &ns::ProjectedPolygons, &ns::PolygonLightPdfs, &ns::AzimuthIntervals}, \
        &ns::Lanes                                                                                 \
  }

// The sets this file was compiled for, best first.
constexpr PacketTarget kTargets[] = {
#if HWY_TARGETS & HWY_AVX3
    PENUMBRA_PACKET_TARGET(HWY_AVX3, N_AVX3),
#endif
#if HWY_TARGETS & HWY_AVX2
    PENUMBRA_PACKET_TARGET(HWY_AVX2, N_AVX2),
#endif
#if HWY_TARGETS & HWY_SSE4
    PENUMBRA_PACKET_TARGET(HWY_SSE4, N_SSE4),
#endif
#if HWY_TARGETS & HWY_EMU128
    PENUMBRA_PACKET_TARGET(HWY_EMU128, N_EMU128),
#endif
#if HWY_TARGETS & HWY_SCALAR
    PENUMBRA_PACKET_TARGET(HWY_SCALAR, N_SCALAR),
#endif
};
#undef PENUMBRA_PACKET_TARGET

// Whether this CPU (and its OS, for the AVX registers) runs Highway's code for `target`: every
// feature Highway compiles that target with (HWY_TARGET_STR in hwy/ops/set_macros-inl.h).
bool runsHere(int64_t target) {
  __builtin_cpu_init();
  const bool sse4 = __builtin_cpu_supports("ssse3") && __builtin_cpu_supports("sse4.1") &&
                    __builtin_cpu_supports("sse4.2") && __builtin_cpu_supports("pclmul") &&
                    __builtin_cpu_supports("aes");
  unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
  const bool f16c = __get_cpuid(1, &eax, &ebx, &ecx, &edx) && (ecx & bit_F16C) != 0;  // not every compiler's
                                                                                      // builtin names it
  const bool avx2 = sse4 && __builtin_cpu_supports("avx") && __builtin_cpu_supports("avx2") &&
                    __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2") &&
                    __builtin_cpu_supports("fma") && f16c;
  const bool avx3 = avx2 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                    __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw");
  if (target == HWY_AVX3) return avx3;
  if (target == HWY_AVX2) return avx2;
  if (target == HWY_SSE4) return sse4;
  return true;  // the portable fallback
}

// The sets this CPU runs, best first (never empty: the fallback runs everywhere).
const std::vector<const PacketTarget*>& runnableTargets() {
  static const std::vector<const PacketTarget*> targets = [] {
    std::vector<const PacketTarget*> t;
    for (const PacketTarget& target : kTargets)
      if (runsHere(target.target)) t.push_back(&target);
    return t;
  }();
  return targets;
}

std::atomic<const PacketTarget*> gForced{nullptr};

const PacketTarget& currentTarget() {
  const PacketTarget* forced = gForced.load(std::memory_order_relaxed);
  return forced ? *forced : *runnableTargets().front();
}

}  // namespace

int packetLanes() {
  return currentTarget().lanes();
}

std::string packetTargetName() {
  return hwy::TargetName(currentTarget().target);
}

std::vector<std::string> availablePacketTargets() {
  std::vector<std::string> names;
  for (const PacketTarget* target : runnableTargets()) names.push_back(hwy::TargetName(target->target));
  return names;
}

bool forcePacketTarget(const std::string& name) {
  gForced.store(nullptr);
  if (name.empty() || name == "auto") return true;
  for (const PacketTarget* target : runnableTargets())
    if (name == hwy::TargetName(target->target)) {
      gForced.store(target);
      return true;
    }
  return false;
}

const PacketKernels& packetKernels() {
  return currentTarget().kernels;
}

}  // namespace penumbra
#endif
