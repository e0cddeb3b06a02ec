// The glossy BSDFs of core/materials/bsdf.cpp (microfacet, roughconductor) in lanes, each lane with its
// own material: f(wo, wi), its density and its sampling. exp (Beckmann's D), log1p (Beckmann's normals)
// and sin and cos (GGX's visible normals) are libm's, called lane by lane; the rest is the scalar
// functions' operations in lanes, branches as masks. Below them, what the kernels see of a packet's
// surfaces: which lanes are glossy (findGlossy), reflection(Le, wi) per lane (reflected), and a
// direction sampled about each shading normal by a warp or the BSDF (surfaceDirection).
// Part of the packet kernels: included by packet_kernels.cpp once per instruction set (Highway's
// re-inclusion toggle below), inside that set's namespace.
#if defined(PENUMBRA_PACKET_BSDF_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PENUMBRA_PACKET_BSDF_INL_H_
#undef PENUMBRA_PACKET_BSDF_INL_H_
#else
#define PENUMBRA_PACKET_BSDF_INL_H_
#endif

#include <hwy/highway.h>

#include <cmath>

#include "core/math/vec.h"
#include "core/render/packet_geometry-inl.h"
#include "core/render/packet_math-inl.h"
#include "core/render/packet_queries.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// PacketGlossyLanes in registers: GlossyReflection's frame and wo, and the Bsdf of each lane.
struct GlossyBsdfLanes {
  FrameF frame;
  V3F wo;
  MF conductor, ggx;
  MF specular;  // hasSpecularLobe: a roughconductor, or a microfacet with ks > 0
  VF alpha, ks, extIOR, intIOR;
  V3F kd, R;
};

HWY_INLINE GlossyBsdfLanes loadGlossyBsdf(const PacketGlossyLanes& g) {
  const DF df;
  const VF zero = hn::Zero(df);
  GlossyBsdfLanes b;
  b.frame = {loadF3(g.s), loadF3(g.t), loadF3(g.n)};
  b.wo = loadF3(g.wo);
  b.conductor = hn::Load(df, g.conductor) != zero;
  b.ggx = hn::Load(df, g.ggx) != zero;
  b.ks = hn::Load(df, g.ks);
  b.specular = hn::Or(b.conductor, b.ks > zero);
  b.alpha = hn::Load(df, g.alpha);
  b.extIOR = hn::Load(df, g.extIOR);
  b.intIOR = hn::Load(df, g.intIOR);
  b.kd = loadF3(g.kd);
  b.R = loadF3(g.R);
  return b;
}

// Frame::toLocal.
HWY_INLINE V3F toLocal(const FrameF& f, const V3F& v) {
  return {dot(v, f.s), dot(v, f.t), dot(v, f.n)};
}

// std::fmax(0, x): 0 for NaN.
HWY_INLINE VF atLeastZero(VF x) {
  return hn::IfThenElseZero(x > hn::Zero(DF()), x);
}

// microfacetD (microfacet_distribution.h), Beckmann or GGX by lane; exp only in the lanes of `needed`.
HWY_INLINE VF microfacetD(MF ggx, const V3F& h, VF alpha, MF needed) {
  const VF zero = hn::Zero(DF());
  const VF c2 = h.z * h.z, s2 = h.x * h.x + h.y * h.y, a2 = alpha * alpha;
  const MF above = h.z > zero;
  const VF e = s2 / (c2 * a2);
  const MF beckmann = hn::AndNot(ggx, hn::And(above, e < setF(87.f)));
  const VF dBeckmann = libmLanes(hn::And(needed, beckmann), hn::Neg(e), [](float x) { return std::exp(x); }) /
                       (setF(kPi) * a2 * c2 * c2);
  const VF d = s2 + a2 * c2;
  const VF dGgx = a2 / (setF(kPi) * d * d);
  return hn::IfThenElse(ggx, hn::IfThenElseZero(above, dGgx), hn::IfThenElseZero(beckmann, dBeckmann));
}

// microfacetG1 (microfacet_distribution.h).
HWY_INLINE VF microfacetG1(MF ggx, const V3F& v, const V3F& h, VF alpha) {
  const VF zero = hn::Zero(DF()), one = setF(1.f);
  const MF faces = dot(v, h) * v.z > zero;
  const VF s2 = v.x * v.x + v.y * v.y, c2 = v.z * v.z;
  const VF b = hn::Abs(v.z) / (alpha * hn::Sqrt(s2));
  const VF beckmann = hn::IfThenElse(
      b >= setF(1.6f), one,
      (setF(3.535f) * b + setF(2.181f) * b * b) / (one + setF(2.276f) * b + setF(2.577f) * b * b));
  const VF ggxG = setF(2.f) / (one + hn::Sqrt(one + alpha * alpha * s2 / c2));
  return hn::IfThenElseZero(faces, hn::IfThenElse(s2 == zero, one, hn::IfThenElse(ggx, ggxG, beckmann)));
}

// fresnelDielectric (fresnel.h).
HWY_INLINE VF fresnelDielectric(VF cosI, VF extIOR, VF intIOR) {
  const VF one = setF(1.f);
  const VF eta = extIOR / intIOR;
  const VF sin2T = eta * eta * atLeastZero(one - cosI * cosI);
  const VF cosT = hn::Sqrt(one - sin2T);
  const VF rs = (extIOR * cosI - intIOR * cosT) / (extIOR * cosI + intIOR * cosT);
  const VF rp = (intIOR * cosI - extIOR * cosT) / (intIOR * cosI + extIOR * cosT);
  const VF F = hn::IfThenElse(sin2T >= one, one, setF(0.5f) * (rs * rs + rp * rp));
  return hn::IfThenElseZero(extIOR != intIOR, F);
}

// evalBsdf and pdfBsdf (bsdf.cpp) of the glossy lanes of m for wi in the local frame: f and the
// density are 0 in the lanes of m where a direction is below the surface; the other lanes hold garbage.
// pdf may be null.
HWY_INLINE void evalGlossyLocal(const GlossyBsdfLanes& b, MF m, const V3F& wi, V3F& f, VF* pdf) {
  const VF zero = hn::Zero(DF());
  const V3F& wo = b.wo;
  const MF above = hn::And(m, hn::And(wo.z > zero, wi.z > zero));
  // halfVectorTerms: the microfacet model's D is Beckmann's.
  const V3F h = normalized(V3F{wo.x + wi.x, wo.y + wi.y, wo.z + wi.z});
  const VF D = microfacetD(b.ggx, h, b.alpha, hn::And(above, b.specular));
  // microfacetSpecular.
  const VF G1o = microfacetG1(b.ggx, wo, h, b.alpha);  // also the visible normals' density
  const VF G = microfacetG1(b.ggx, wi, h, b.alpha) * G1o;
  const VF spec = hn::IfThenElseZero(D != zero, D * G / (setF(4.f) * wi.z * wo.z));
  // evalAbove: kd/π + ks spec F (microfacet), R spec (roughconductor).
  const VF F = fresnelDielectric(dot(h, wi), b.extIOR, b.intIOR);
  const VF lobe = hn::IfThenElseZero(hn::And(b.specular, spec > zero), b.ks * spec * F);
  const VF invPi = setF(kInvPi);
  const V3F microfacet{b.kd.x * invPi + lobe, b.kd.y * invPi + lobe, b.kd.z * invPi + lobe};
  const V3F conductor{b.R.x * spec, b.R.y * spec, b.R.z * spec};
  const V3F model = select(b.conductor, conductor, microfacet);
  f = {hn::IfThenElseZero(above, model.x), hn::IfThenElseZero(above, model.y),
       hn::IfThenElseZero(above, model.z)};
  if (!pdf) return;
  // pdfAbove: specularPdf is the reflected density of the sampled normals (all normals, D cos θh, or
  // GGX's visible normals).
  const VF visiblePdf = G1o * atLeastZero(dot(wo, h)) * D / wo.z;
  const VF normalPdf = hn::IfThenElse(b.ggx, visiblePdf, D * h.z);
  const VF c = hn::Abs(dot(wi, h));
  const VF specularPdf = hn::IfThenElseZero(c > zero, normalPdf / (setF(4.f) * c));
  const VF diffusePdf = (setF(1.f) - b.ks) * wi.z * invPi;
  const VF microfacetPdf = hn::IfThenElse(b.ks > zero, diffusePdf + b.ks * specularPdf, diffusePdf);
  *pdf = hn::IfThenElseZero(above, hn::IfThenElse(b.conductor, specularPdf, microfacetPdf));
}

// evalGlossyLocal for a world direction (GlossyReflection's f and pdf).
HWY_INLINE void evalGlossy(const GlossyBsdfLanes& b, MF m, const V3F& wiWorld, V3F& f, VF* pdf) {
  evalGlossyLocal(b, m, toLocal(b.frame, wiWorld), f, pdf);
}

// reflectAbout (microfacet_distribution.h): v mirrored about the unit normal n.
HWY_INLINE V3F reflectAbout(const V3F& v, const V3F& n) {
  const VF twice = setF(2.f) * dot(v, n);
  return {n.x * twice - v.x, n.y * twice - v.y, n.z * twice - v.z};
}

// Warp::squareToBeckmann (warp_sphere.cpp); log1p only in the lanes of m.
HWY_INLINE V3F beckmannNormal(MF m, VF u0, VF u1, VF alpha) {
  const VF one = setF(1.f);
  const VF log = libmLanes(m, hn::Neg(u0), [](float x) { return std::log1p(x); });
  const VF tan2 = hn::Neg(alpha) * alpha * log;
  const VF cosTheta = one / hn::Sqrt(one + tan2);
  const VF sinTheta = hn::Sqrt(tan2 / (one + tan2));
  VF sinPhi, cosPhi;
  sinCosTurns(u1, sinPhi, cosPhi);
  return {sinTheta * cosPhi, sinTheta * sinPhi, cosTheta};
}

// sampleGgxVisibleNormal (microfacet_distribution.h); cos and sin only in the lanes of m.
HWY_INLINE V3F ggxVisibleNormal(MF m, const V3F& wo, VF alpha, VF u0, VF u1) {
  const VF zero = hn::Zero(DF()), one = setF(1.f);
  const V3F vh = normalized(V3F{alpha * wo.x, alpha * wo.y, wo.z});
  const VF lensq = vh.x * vh.x + vh.y * vh.y;
  const VF inv = one / hn::Sqrt(lensq);
  const MF tilted = lensq > zero;
  const V3F t1{hn::IfThenElse(tilted, hn::Neg(vh.y) * inv, one), hn::IfThenElseZero(tilted, vh.x * inv),
               hn::IfThenElseZero(tilted, zero * inv)};
  const V3F t2 = cross(vh, t1);
  const VF r = hn::Sqrt(u0), phi = setF(2.f * kPi) * u1;
  const VF p1 = r * libmLanes(m, phi, [](float x) { return std::cos(x); });
  const VF s = setF(0.5f) * (one + vh.z);
  const VF p2 = (one - s) * hn::Sqrt(atLeastZero(one - p1 * p1)) +
                s * (r * libmLanes(m, phi, [](float x) { return std::sin(x); }));
  const VF up = hn::Sqrt(atLeastZero(one - p1 * p1 - p2 * p2));
  const V3F nh{t1.x * p1 + t2.x * p2 + vh.x * up, t1.y * p1 + t2.y * p2 + vh.y * up,
               t1.z * p1 + t2.z * p2 + vh.z * up};
  return normalized(V3F{alpha * nh.x, alpha * nh.y, atLeastZero(nh.z)});
}

// sampleBsdf (bsdf.cpp) in the glossy lanes of m from the draw (u0, u1), as bsdfSampledRadiance takes
// it: wi in the local frame, the weight f cos θ / pdf and the density; valid where the density is
// positive and wi above the surface (the scalar sample's rejections are invalid lanes here).
struct GlossySample {
  V3F wi, weight;
  VF pdf;
  MF valid;
};
HWY_INLINE GlossySample sampleGlossy(const GlossyBsdfLanes& b, MF m, VF u0, VF u1) {
  const VF zero = hn::Zero(DF()), one = setF(1.f);
  // The microfacet model picks its lobe by u0 and rescales u0 to [0,1) for the lobe's warp.
  const MF belowKs = u0 < b.ks;
  const VF rescaled = hn::IfThenElse(belowKs, u0 / b.ks, (u0 - b.ks) / (one - b.ks));
  const VF u = hn::IfThenElse(
      b.conductor, u0, hn::IfThenElse(setF(kOneMinusEpsilon) < rescaled, setF(kOneMinusEpsilon), rescaled));
  const MF specular = hn::Or(b.conductor, belowKs);
  const MF ggx = hn::And(b.ggx, b.conductor);
  const V3F beckmann = beckmannNormal(hn::AndNot(ggx, hn::And(m, specular)), u, u1, b.alpha);
  const V3F visible = ggxVisibleNormal(hn::And(m, ggx), b.wo, b.alpha, u, u1);
  const V3F normal = select(ggx, visible, beckmann);
  GlossySample s;
  s.wi = select(specular, reflectAbout(b.wo, normal), squareToCosineHemisphere(u, u1));
  MF valid = hn::And(m, hn::And(b.wo.z > zero, s.wi.z > zero));
  V3F f;
  evalGlossyLocal(b, valid, s.wi, f, &s.pdf);
  valid = hn::And(valid, hn::And(s.pdf > zero, s.pdf < setF(INFINITY)));
  const VF cosOverPdf = s.wi.z / s.pdf;
  s.weight = {f.x * cosOverPdf, f.y * cosOverPdf, f.z * cosOverPdf};
  s.valid = hn::And(valid, validRadiance(s.weight));
  return s;
}

// ---- The kernels' view of a packet's surfaces ----------------------------------------------------

// The glossy surfaces among a packet's shaded lanes, whose BSDFs the functions above evaluate and
// sample.
struct GlossySurfaces {
  MF lanes;  // the shaded lanes whose surface is glossy
  bool any;  // lanes is not empty (the rest is filled only then)
  PacketGlossyLanes data;
  GlossyBsdfLanes bsdf;  // data in registers
};

// The glossy lanes among `shaded`, with their frames and wo.
HWY_INLINE void findGlossy(const PacketScene& scene, const PacketRays& rays, const PacketHit& h, MF shaded,
                           GlossySurfaces& g) {
  const DF df;
  g.any = false;
  g.lanes = hn::FirstN(df, 0);
  if (!scene.anyGlossy) return;
  g.lanes = hn::And(shaded, h.glossy);
  g.any = !hn::AllFalse(df, g.lanes);
  if (!g.any) return;
  HWY_ALIGN float object[kMaxPacketLanes], active[kMaxPacketLanes];
  PacketColorLanes ns;
  hn::Store(h.object, df, object);
  hn::Store(hn::IfThenElseZero(g.lanes, setF(1.f)), df, active);
  storeF3(h.ns, ns.c);
  queryGlossyLanes(*scene.scene, rays, object, ns.c, active, int(hn::Lanes(df)), g.data);
  g.bsdf = loadGlossyBsdf(g.data);
}

// reflection(Le, wi) (reflection.h) in the lanes of m: Le f(wo, wi) on glossy surfaces, Le on diffuse
// ones (whose f is applied to the whole estimate); the other lanes keep Le. With glossyPdf, also the
// glossy lanes' GlossyReflection::pdf of wi there (0 elsewhere).
HWY_INLINE V3F reflected(const GlossySurfaces& g, MF m, const V3F& Le, const V3F& wi,
                         VF* glossyPdf = nullptr) {
  const DF df;
  if (glossyPdf) *glossyPdf = hn::Zero(df);
  if (!g.any) return Le;
  const MF glossy = hn::And(m, g.lanes);
  if (hn::AllFalse(df, glossy)) return Le;
  V3F f;
  VF pdf;
  evalGlossy(g.bsdf, glossy, wi, f, glossyPdf ? &pdf : nullptr);
  if (glossyPdf) *glossyPdf = hn::IfThenElseZero(glossy, pdf);
  return select(glossy, times(Le, f), Le);
}

// Sampler draw j of every lane.
HWY_INLINE void loadDraw(const PacketDraws& draws, size_t j, VF& u0, VF& u1) {
  const DF df;
  u0 = hn::LoadU(df, draws.draw[j].u[0]);
  u1 = hn::LoadU(df, draws.draw[j].u[1]);
}

// A direction about +z by warp kWarp (Warp::squareToCosineHemisphere or squareToUniformHemisphere).
template <HemisphereWarp kWarp>
HWY_INLINE V3F hemisphereDirection(VF u0, VF u1) {
  return kWarp == HemisphereWarp::Cosine ? squareToCosineHemisphere(u0, u1)
                                         : directionFromOneMinusCos(u0, u1);
}

// A direction sampled about the shading normal from draw j: by warp kWarp, or on glossy lanes (with
// bsdfSampled) by the BSDF's sampler (bsdfSampledRadiance). Le · weight · cosOverPdf is its
// contribution on a diffuse lane before f (reflection.h) and on a glossy BSDF-sampled one.
struct SurfaceDirection {
  V3F w;
  MF valid;       // leavesSurface's test of the local direction (the geometric side is the caller's)
  VF cosOverPdf;  // π for the cosine warp, 2π cos θ for the uniform one, 1 on BSDF-sampled lanes
  VF pdf;         // the solid-angle density (the cosine warp's or the BSDF's)
  V3F weight;     // 1, or the BSDF sample's f cos θ / pdf
};

template <HemisphereWarp kWarp>
HWY_INLINE SurfaceDirection surfaceDirection(const GlossySurfaces& g, bool bsdfSampled, const FrameF& frame,
                                             const PacketDraws& draws, size_t j) {
  const DF df;
  VF u0, u1;
  loadDraw(draws, j, u0, u1);
  const V3F local = hemisphereDirection<kWarp>(u0, u1);
  const VF one = setF(1.f);
  SurfaceDirection d{toWorld(frame, local),
                     local.z > hn::Zero(df),
                     kWarp == HemisphereWarp::Cosine ? setF(kPi) : setF(2.f * kPi) * local.z,
                     kWarp == HemisphereWarp::Cosine ? local.z * setF(kInvPi) : setF(0.5f * kInvPi),
                     {one, one, one}};
  if (!bsdfSampled || !g.any) return d;
  const GlossySample s = sampleGlossy(g.bsdf, g.lanes, u0, u1);
  d.w = select(g.lanes, toWorld(g.bsdf.frame, s.wi), d.w);
  d.valid = hn::Or(hn::And(g.lanes, s.valid), hn::AndNot(g.lanes, d.valid));
  d.cosOverPdf = hn::IfThenElse(g.lanes, one, d.cosOverPdf);
  d.pdf = hn::IfThenElse(g.lanes, s.pdf, d.pdf);
  d.weight = select(g.lanes, s.weight, d.weight);
  return d;
}

}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#endif
