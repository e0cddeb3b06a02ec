// The packet kernels, compiled by Highway once per instruction set (this file includes itself through
// hwy/foreach_target.h) and chosen at run time (HWY_DYNAMIC_DISPATCH). Each function mirrors, lane by
// lane, the scalar function its comment names: the same float and double operations in the same
// order, branches as masks. The file is compiled without floating-point contraction, so no
// multiply-add is fused where the scalar code rounds twice.

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

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace {

namespace hn = hwy::HWY_NAMESPACE;
using DD = hn::ScalableTag<double>;
using DF = hn::Rebind<float, DD>;
using DI = hn::Rebind<int32_t, DD>;
using DU = hn::Rebind<uint32_t, DD>;
using VD = hn::Vec<DD>;
using VF = hn::Vec<DF>;
using MD = hn::Mask<DD>;
using MF = hn::Mask<DF>;

struct V3F {
  VF x, y, z;
};
struct V3D {
  VD x, y, z;
};

HWY_INLINE VF setF(float v) {
  return hn::Set(DF(), v);
}
HWY_INLINE VD setD(double v) {
  return hn::Set(DD(), v);
}
HWY_INLINE V3F setF3(const float* v) {
  return {setF(v[0]), setF(v[1]), setF(v[2])};
}
HWY_INLINE V3F setF3(const Vec3& v) {
  return {setF(v.x), setF(v.y), setF(v.z)};
}
HWY_INLINE V3D promote(const V3F& v) {
  const DD dd;
  return {hn::PromoteTo(dd, v.x), hn::PromoteTo(dd, v.y), hn::PromoteTo(dd, v.z)};
}
HWY_INLINE VD promote(VF v) {
  return hn::PromoteTo(DD(), v);
}
HWY_INLINE VF demote(VD v) {
  return hn::DemoteTo(DF(), v);
}
HWY_INLINE V3F demote(const V3D& v) {
  return {demote(v.x), demote(v.y), demote(v.z)};
}
// A float-lane mask as a double-lane mask and back (same lane count).
HWY_INLINE MD toD(MF m) {
  return hn::PromoteTo(DD(), hn::IfThenElseZero(m, setF(1.f))) == setD(1.0);
}
HWY_INLINE MF toF(MD m) {
  return hn::DemoteTo(DF(), hn::IfThenElseZero(m, setD(1.0))) == setF(1.f);
}

// glm::dot: (a.x b.x + a.y b.y) + a.z b.z.
template <class V3>
HWY_INLINE auto dot(const V3& a, const V3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class V3, class M>
HWY_INLINE V3 select(M m, const V3& a, const V3& b) {
  return {hn::IfThenElse(m, a.x, b.x), hn::IfThenElse(m, a.y, b.y), hn::IfThenElse(m, a.z, b.z)};
}
// std::max(a, b) and glm::max(a, b): (a < b) ? b : a, NaN in a kept.
HWY_INLINE VF maxOf(VF a, VF b) {
  return hn::IfThenElse(a < b, b, a);
}
// maxAbsComponent.
HWY_INLINE VF maxAbs(const V3F& v) {
  return maxOf(hn::Abs(v.x), maxOf(hn::Abs(v.y), hn::Abs(v.z)));
}

// sinCosTurns (core/math/sincos_turns.h).
HWY_INLINE void sinCosTurns(VF turns, VF& sinOut, VF& cosOut) {
  using K = SinCosCoefficients;
  const DF df;
  const VF quarters = setF(4.f) * turns;
  const VF bias = setF(K::kRoundingBias);
  const VF q = hn::IfThenElse(hn::Abs(quarters) < setF(0x1p22f), (quarters + bias) - bias, quarters);
  const VF x = (quarters - q) * setF(kPiOver2);
  const VF x2 = x * x;
  const VF s = x + x * x2 * (setF(K::kSin1) + x2 * (setF(K::kSin2) + x2 * setF(K::kSin3)));
  const VF c =
      setF(1.f) - setF(0.5f) * x2 + x2 * x2 * (setF(K::kCos1) + x2 * (setF(K::kCos2) + x2 * setF(K::kCos3)));
  // std::min(2^24, std::max(-2^24, q)), NaN going to −2^24 as there.
  const VF lo = hn::IfThenElse(setF(-0x1p24f) < q, q, setF(-0x1p24f));
  const VF clamped = hn::IfThenElse(lo < setF(0x1p24f), lo, setF(0x1p24f));
  const DU du;
  const auto quadrant = hn::BitCast(du, hn::ConvertTo(DI(), clamped));
  const MF odd = hn::RebindMask(df, hn::And(quadrant, hn::Set(du, 1u)) != hn::Zero(du));
  const auto sinSign = hn::ShiftLeft<30>(hn::And(quadrant, hn::Set(du, 2u)));
  const auto cosSign = hn::ShiftLeft<30>(hn::And(quadrant + hn::Set(du, 1u), hn::Set(du, 2u)));
  sinOut = hn::BitCast(df, hn::Xor(hn::BitCast(du, hn::IfThenElse(odd, c, s)), sinSign));
  cosOut = hn::BitCast(df, hn::Xor(hn::BitCast(du, hn::IfThenElse(odd, s, c)), cosSign));
}

// Sphere::mayHit.
HWY_INLINE MF sphereMayHit(const PacketSphere& s, const V3F& o, const V3F& d) {
  const V3F f{o.x - setF(s.center[0]), o.y - setF(s.center[1]), o.z - setF(s.center[2])};
  const VF a = dot(d, d), b = dot(f, d), ff = dot(f, f);
  return hn::Not(a * (ff - setF(s.radius * s.radius)) - b * b > setF(1e-5f) * a * ff);
}

// Sphere::roots after the pre-test `may`: t0 <= t1 in the lanes of `valid`.
struct Roots {
  VD t0, t1;
  MD valid;
};
HWY_INLINE Roots sphereRoots(const PacketSphere& s, const V3D& o, const V3D& d, MD may) {
  const V3D f{o.x - setD(double(s.center[0])), o.y - setD(double(s.center[1])),
              o.z - setD(double(s.center[2]))};
  const double r = s.radius;
  const VD a = dot(d, d);
  const VD invA = setD(1.0) / a;
  const VD b = dot(f, d);
  const VD bOverA = b * invA;
  const V3D v{f.x - bOverA * d.x, f.y - bOverA * d.y, f.z - bOverA * d.z};
  const VD disc = setD(r * r) - dot(v, v);
  const VD c = dot(f, f) - setD(r * r);
  const VD q = hn::Neg(b + hn::CopySign(hn::Sqrt(a * disc), b));
  const VD t1 = q * invA;
  const VD t0 = hn::IfThenElse(q != hn::Zero(DD()), c / q, t1);
  const MD swap = t0 > t1;
  return {hn::IfThenElse(swap, t1, t0), hn::IfThenElse(swap, t0, t1), hn::And(may, disc >= hn::Zero(DD()))};
}

// intersectParallelogram: the lanes hit in (tMin, tMax), with their t.
HWY_INLINE MF parallelogramHit(const Parallelogram& q, const V3F& o, const V3F& d, VF tMin, VF tMax, VF& t) {
  const V3F n = setF3(q.n);
  const VF denom = dot(n, d);
  const VF h = dot(n, o) - setF(q.planeOffset);
  const VF ndSum = hn::Abs(n.x * d.x) + hn::Abs(n.y * d.y) + hn::Abs(n.z * d.z);
  const VF noSum = hn::Abs(n.x * o.x) + hn::Abs(n.y * o.y) + hn::Abs(n.z * o.z);
  MF ok = hn::Abs(denom) > setF(detail::kParallelogramGamma3) * ndSum;
  ok =
      hn::And(ok, hn::Abs(h) > setF(detail::kParallelogramGamma7) * (noSum + setF(std::fabs(q.planeOffset))));
  t = hn::Neg(h) / denom;
  ok = hn::And(ok, hn::And(t > tMin, t < tMax));
  const V3F rel{(o.x - setF(q.p0.x)) + t * d.x, (o.y - setF(q.p0.y)) + t * d.y,
                (o.z - setF(q.p0.z)) + t * d.z};
  const VF u = dot(setF3(q.du), rel), v = dot(setF3(q.dv), rel);
  const VF zero = hn::Zero(DF()), one = setF(1.f);
  ok = hn::And(ok, hn::And(hn::And(u >= zero, u <= one), hn::And(v >= zero, v <= one)));
  return ok;
}

// SceneGeometry::occludedByFlatShapes for the lanes of `active` (tMin = 0): which are blocked.
HWY_INLINE MF occluded(const PacketScene& scene, const V3F& o, const V3F& d, VF tMax, int32_t skipSphere,
                       MF active) {
  const DF df;
  MF blocked = hn::FirstN(df, 0);
  const VF zero = hn::Zero(df);
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    if (static_cast<int32_t>(i) == skipSphere) continue;
    const MF may = hn::AndNot(blocked, hn::And(active, sphereMayHit(scene.spheres[i], o, d)));
    if (hn::AllFalse(df, may)) continue;
    const Roots r = sphereRoots(scene.spheres[i], promote(o), promote(d), toD(may));
    const VD tMinD = hn::Zero(DD()), tMaxD = promote(tMax);
    const MD in0 = hn::And(r.t0 > tMinD, r.t0 < tMaxD), in1 = hn::And(r.t1 > tMinD, r.t1 < tMaxD);
    blocked = hn::Or(blocked, toF(hn::And(r.valid, hn::Or(in0, in1))));
  }
  for (const PacketQuad& q : scene.quads) {
    if (hn::AllFalse(df, hn::AndNot(blocked, active))) break;
    VF t;
    blocked = hn::Or(blocked, hn::And(active, parallelogramHit(q.shape, o, d, zero, tMax, t)));
  }
  return blocked;
}

// What the camera rays hit, as ShadingPoint holds it, with the material's data.
struct PacketHit {
  MF hit;         // anything hit
  V3F p, ng, ns;  // ng and ns flipped to the ray's side (ShadingPoint)
  VF offsetScale;
  MF shades;  // the albedo is not black
  V3F albedoOverPi;
  V3F emitted;  // emittedAt
};

HWY_INLINE void setObject(const PacketObject& object, MF m, const V3F& rayD, const V3F& ngUnflipped,
                          PacketHit& h) {
  h.albedoOverPi = select(m, setF3(object.albedoOverPi), h.albedoOverPi);
  if (object.shades) h.shades = hn::Or(h.shades, m);
  if (object.emits) {
    // SphereLight::eval: the outer side only.
    const MF facing = hn::And(m, dot(ngUnflipped, rayD) < hn::Zero(DF()));
    h.emitted = select(facing, setF3(object.radiance), h.emitted);
  }
}

// SceneGeometry::intersect over the flat spheres and parallelograms, fillHit, emittedAt and the
// ShadingPoint's normals.
HWY_INLINE PacketHit nearestHit(const PacketScene& scene, const V3F& o, const V3F& d, VF tMin, VF tMax) {
  const DF df;
  const VF none = setF(-1.f);
  VF sphereIndex = none, quadIndex = none;
  const V3D oD = promote(o), dD = promote(d);
  const VD tMinD = promote(tMin);
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const MF may = sphereMayHit(scene.spheres[i], o, d);
    if (hn::AllFalse(df, may)) continue;
    const Roots r = sphereRoots(scene.spheres[i], oD, dD, toD(may));
    const VD tMaxD = promote(tMax);
    const MD in0 = hn::And(r.t0 > tMinD, r.t0 < tMaxD), in1 = hn::And(r.t1 > tMinD, r.t1 < tMaxD);
    const MF hit = toF(hn::And(r.valid, hn::Or(in0, in1)));
    tMax = hn::IfThenElse(hit, demote(hn::IfThenElse(in0, r.t0, r.t1)), tMax);
    sphereIndex = hn::IfThenElse(hit, setF(float(i)), sphereIndex);
  }
  for (size_t j = 0; j < scene.quads.size(); ++j) {
    VF t;
    const MF hit = parallelogramHit(scene.quads[j].shape, o, d, tMin, tMax, t);
    tMax = hn::IfThenElse(hit, t, tMax);
    quadIndex = hn::IfThenElse(hit, setF(float(j)), quadIndex);
  }

  PacketHit h;
  const VF zero = hn::Zero(df);
  h.p = h.ng = h.ns = h.albedoOverPi = h.emitted = {zero, zero, zero};
  h.offsetScale = zero;
  h.shades = hn::FirstN(df, 0);
  const MF quadHit = quadIndex >= zero;
  h.hit = hn::Or(quadHit, sphereIndex >= zero);
  const VD tD = promote(tMax);
  const V3D along{oD.x + tD * dD.x, oD.y + tD * dD.y, oD.z + tD * dD.z};  // o + t·d in double
  for (size_t j = 0; j < scene.quads.size(); ++j) {
    const MF m = quadIndex == setF(float(j));
    if (hn::AllFalse(df, m)) continue;
    // fillParallelogramHit: o + t·d moved onto the plane in double.
    const Parallelogram& q = scene.quads[j].shape;
    const V3D n{setD(double(q.n.x)), setD(double(q.n.y)), setD(double(q.n.z))};
    const VD off = dot(n, along) - setD(double(q.planeOffset));
    const V3F p = demote(V3D{along.x - n.x * off, along.y - n.y * off, along.z - n.z * off});
    h.p = select(m, p, h.p);
    h.ng = select(m, setF3(q.n), h.ng);
    h.ns = select(m, setF3(q.ns), h.ns);
    h.offsetScale = hn::IfThenElse(m, maxAbs(p), h.offsetScale);
    setObject(scene.objects[scene.quads[j].object], m, d, setF3(q.n), h);
  }
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const MF m = hn::AndNot(quadHit, sphereIndex == setF(float(i)));
    if (hn::AllFalse(df, m)) continue;
    // Sphere::fillHit: p re-projected onto the sphere in double.
    const PacketSphere& s = scene.spheres[i];
    const V3D c{setD(double(s.center[0])), setD(double(s.center[1])), setD(double(s.center[2]))};
    V3D n{along.x - c.x, along.y - c.y, along.z - c.z};
    const VD len = hn::Sqrt(dot(n, n));
    const MD positive = len > hn::Zero(DD());
    const VD invLen = setD(1.0) / len;
    n = {hn::IfThenElseZero(positive, n.x * invLen), hn::IfThenElseZero(positive, n.y * invLen),
         hn::IfThenElse(positive, n.z * invLen, setD(1.0))};
    const VD r = setD(double(s.radius));
    const V3F p = demote(V3D{c.x + r * n.x, c.y + r * n.y, c.z + r * n.z});
    const V3F ng = demote(n);
    h.p = select(m, p, h.p);
    h.ng = select(m, ng, h.ng);
    h.ns = select(m, ng, h.ns);
    h.offsetScale = hn::IfThenElse(m, maxOf(maxAbs(p), setF(s.offsetScale)), h.offsetScale);
    setObject(scene.objects[s.object], m, d, ng, h);
  }
  // ShadingPoint: normals towards the viewer; a shading normal on the other side falls back to ng.
  const MF backFacing = dot(h.ng, d) > zero;
  h.ng = select(backFacing, V3F{hn::Neg(h.ng.x), hn::Neg(h.ng.y), hn::Neg(h.ng.z)}, h.ng);
  h.ns = select(backFacing, V3F{hn::Neg(h.ns.x), hn::Neg(h.ns.y), hn::Neg(h.ns.z)}, h.ns);
  h.ns = select(dot(h.ns, h.ng) < zero, h.ng, h.ns);
  return h;
}

// A light sample for every lane: the lanes where it is valid with a positive pdf and radiance.
struct PacketLightSample {
  MF valid;
  V3F wi;
  VF dist, pdf;
};

// SphereLight::sampleArea (with Warp::squareToUniformSphere).
HWY_INLINE PacketLightSample sampleArea(const PacketLight& light, const V3F& x, VF u0, VF u1) {
  const DF df;
  const DD dd;
  const VF w = setF(2.f) * u0;
  const VF s2 = w * (setF(2.f) - w);
  const VF sinTheta = hn::Sqrt(hn::IfThenElse(s2 < hn::Zero(df), hn::Zero(df), s2));
  VF sinPhi, cosPhi;
  sinCosTurns(u1, sinPhi, cosPhi);
  const V3F n{sinTheta * cosPhi, sinTheta * sinPhi, setF(1.f) - w};
  const VF r = setF(light.radius);
  const V3F p{setF(light.center[0]) + r * n.x, setF(light.center[1]) + r * n.y,
              setF(light.center[2]) + r * n.z};
  const V3D xD = promote(x), pD = promote(p);
  const V3D toP{pD.x - xD.x, pD.y - xD.y, pD.z - xD.z};
  const VD dist2 = dot(toP, toP);
  const VD nDotToP = dot(promote(n), toP);
  const VD zero = hn::Zero(dd);
  const VD dist = hn::Sqrt(dist2);
  const VD invDist = setD(1.0) / dist;
  const double fourPiR2 = 4.0 * kPiD * double(light.radius) * light.radius;
  const VD pdf = dist2 * dist / (setD(fourPiR2) * hn::Abs(nDotToP));
  // Far-side points (n·toP ≥ 0) have Le = 0: skipped as the scalar loop skips black samples.
  const MD valid = hn::And(hn::And(dist2 > zero, nDotToP < zero), pdf <= setD(SphereLight::kMaxPdf));
  PacketLightSample s;
  s.pdf = demote(pdf);
  s.valid = hn::And(toF(valid), s.pdf > hn::Zero(df));
  s.wi = demote(V3D{toP.x * invDist, toP.y * invDist, toP.z * invDist});
  s.dist = demote(dist);
  return s;
}

// SphereLight::sampleSolidAngle (with subtendedCone and orthonormalBasis).
HWY_INLINE PacketLightSample sampleSolidAngle(const PacketLight& light, const V3F& x, VF u0, VF u1) {
  const DD dd;
  const double r = light.radius;
  const V3D xD = promote(x);
  const V3D dc{setD(double(light.center[0])) - xD.x, setD(double(light.center[1])) - xD.y,
               setD(double(light.center[2])) - xD.z};
  const VD d = hn::Sqrt(dot(dc, dc));
  const VD invD = setD(1.0) / d;
  const V3D wc{dc.x * invD, dc.y * invD, dc.z * invD};
  const VD sinMax = setD(r) * invD;
  const VD sin2Max = sinMax * sinMax;
  const VD cosMax = hn::Sqrt((d - setD(r)) * (d + setD(r))) * invD;
  const VD oneMinusCos = sin2Max / (setD(1.0) + cosMax);
  // subtendedCone's tests: outside the sphere, a finite distance, a cone whose pdf fits a float.
  MD valid = hn::And(d >= setD(r), d < setD(INFINITY));
  valid = hn::And(valid, oneMinusCos >= setD(SphereLight::kMinOneMinusCos));

  const VD oneMinusCosT = promote(u0) * oneMinusCos;
  const VD cosT = setD(1.0) - oneMinusCosT;
  const VD sin2T = oneMinusCosT * (setD(2.0) - oneMinusCosT);
  const VD sinT = hn::Sqrt(sin2T);
  VF sinPhiF, cosPhiF;
  sinCosTurns(u1, sinPhiF, cosPhiF);
  const VD cosPhi = promote(cosPhiF), sinPhi = promote(sinPhiF);
  const VD invSinMax = d / setD(r);
  const VD ratio = sin2T * invSinMax;
  const VD zero = hn::Zero(dd);
  // std::max(0.0, v): NaN goes to 0 as there.
  auto clampPositive = [&](VD v) { return hn::IfThenElse(zero < v, v, zero); };
  const VD cosA = ratio + cosT * hn::Sqrt(clampPositive(setD(1.0) - ratio * invSinMax));
  const VD sinA = hn::Sqrt(clampPositive(setD(1.0) - cosA * cosA));
  // orthonormalBasis(wc, s, t).
  const VD sign = hn::CopySign(setD(1.0), wc.z);
  const VD a = setD(-1.0) / (sign + wc.z);
  const VD b = wc.x * wc.y * a;
  const V3D s{setD(1.0) + sign * wc.x * wc.x * a, sign * b, hn::Neg(sign) * wc.x};
  const V3D t{b, sign + wc.y * wc.y * a, hn::Neg(wc.y)};
  const V3D lateral{cosPhi * s.x + sinPhi * t.x, cosPhi * s.y + sinPhi * t.y, cosPhi * s.z + sinPhi * t.z};
  const V3D wi{sinT * lateral.x + cosT * wc.x, sinT * lateral.y + cosT * wc.y,
               sinT * lateral.z + cosT * wc.z};
  const V3D n{sinA * lateral.x - cosA * wc.x, sinA * lateral.y - cosA * wc.y, sinA * lateral.z - cosA * wc.z};
  const VD rD = setD(r);
  const V3D p{setD(double(light.center[0])) + rD * n.x, setD(double(light.center[1])) + rD * n.y,
              setD(double(light.center[2])) + rD * n.z};
  const V3D toP{p.x - xD.x, p.y - xD.y, p.z - xD.z};
  PacketLightSample out;
  out.wi = demote(wi);
  out.dist = demote(hn::Sqrt(dot(toP, toP)));
  out.pdf = demote(setD(1.0) / (setD(2.0 * kPiD) * oneMinusCos));
  out.valid = hn::And(toF(valid), out.pdf > hn::Zero(DF()));
  return out;
}

// LightDirectIntegrator<measure, All> through directRadiance: every light, every sample, shadow
// tested; the mean over the samples, times albedo/π, plus the emission at the hit.
template <LightMeasure kMeasure>
HWY_INLINE void shadeDirect(const PacketScene& scene, const PacketRays& rays, const PacketDraws& draws,
                            PacketRadiance& out) {
  const DF df;
  const V3F o{hn::LoadU(df, rays.o[0]), hn::LoadU(df, rays.o[1]), hn::LoadU(df, rays.o[2])};
  const V3F d{hn::LoadU(df, rays.d[0]), hn::LoadU(df, rays.d[1]), hn::LoadU(df, rays.d[2])};
  const PacketHit h = nearestHit(scene, o, d, hn::LoadU(df, rays.tMin), hn::LoadU(df, rays.tMax));
  const VF zero = hn::Zero(df);
  V3F E{zero, zero, zero};
  const MF shaded = hn::And(h.hit, h.shades);
  if (!hn::AllFalse(df, shaded)) {
    const int samples = scene.lightSamples;
    for (size_t l = 0; l < scene.lights.size(); ++l) {
      const PacketLight& light = scene.lights[l];
      if (light.black || !(light.radius > 0.f)) continue;
      const VF lightScale = setF(light.scale);
      for (int i = 0; i < samples; ++i) {
        const size_t j = l * size_t(samples) + size_t(i);
        const VF u0 = hn::LoadU(df, draws.u[j][0]), u1 = hn::LoadU(df, draws.u[j][1]);
        const PacketLightSample s = kMeasure == LightMeasure::Area ? sampleArea(light, h.p, u0, u1)
                                                                   : sampleSolidAngle(light, h.p, u0, u1);
        // unoccludedLightSample: above the surface (leavesSurface), then the shadow ray.
        const VF cosTheta = dot(h.ns, s.wi);
        const VF wiDotNg = dot(s.wi, h.ng);
        MF lit = hn::And(hn::And(shaded, s.valid), hn::And(cosTheta > zero, wiDotNg > zero));
        if (hn::AllFalse(df, lit)) continue;
        // ShadingPoint::spawnShadowRayAlong with offsetRayOrigin.
        const VF offset = setF(kRayOffsetScale) * h.offsetScale;
        const VF signedOffset = hn::IfThenElse(wiDotNg < zero, hn::Neg(offset), offset);
        const V3F origin{h.p.x + h.ng.x * signedOffset, h.p.y + h.ng.y * signedOffset,
                         h.p.z + h.ng.z * signedOffset};
        const VF larger = maxOf(lightScale, h.offsetScale);
        const VF tMax = s.dist - setF(kRayOffsetScale) * (setF(2.f) * larger + h.offsetScale);
        lit = hn::AndNot(occluded(scene, origin, s.wi, tMax, light.geometrySphere, lit), lit);
        const VF cosOverPdf = cosTheta / s.pdf;
        E.x = hn::IfThenElse(lit, E.x + setF(light.radiance[0]) * cosOverPdf, E.x);
        E.y = hn::IfThenElse(lit, E.y + setF(light.radiance[1]) * cosOverPdf, E.y);
        E.z = hn::IfThenElse(lit, E.z + setF(light.radiance[2]) * cosOverPdf, E.z);
      }
    }
    const VF invSamples = setF(1.f / float(samples));
    // directRadiance: L + albedo/π · (delta lights' 0 + the estimate).
    E = {zero + E.x * invSamples, zero + E.y * invSamples, zero + E.z * invSamples};
  }
  const VF Lx = hn::IfThenElse(shaded, h.emitted.x + h.albedoOverPi.x * E.x, h.emitted.x);
  const VF Ly = hn::IfThenElse(shaded, h.emitted.y + h.albedoOverPi.y * E.y, h.emitted.y);
  const VF Lz = hn::IfThenElse(shaded, h.emitted.z + h.albedoOverPi.z * E.z, h.emitted.z);
  hn::StoreU(Lx, df, out.L[0]);
  hn::StoreU(Ly, df, out.L[1]);
  hn::StoreU(Lz, df, out.L[2]);
}

}  // namespace

void ShadeDirectArea(const PacketScene& scene, const PacketRays& rays, const PacketDraws& draws,
                     PacketRadiance& out) {
  shadeDirect<LightMeasure::Area>(scene, rays, draws, out);
}
void ShadeDirectSolidAngle(const PacketScene& scene, const PacketRays& rays, const PacketDraws& draws,
                           PacketRadiance& out) {
  shadeDirect<LightMeasure::SolidAngle>(scene, rays, draws, out);
}
int Lanes() {
  return static_cast<int>(hn::Lanes(DD()));
}
const char* TargetName() {
  return hwy::TargetName(HWY_TARGET);
}

}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace penumbra {

HWY_EXPORT(ShadeDirectArea);
HWY_EXPORT(ShadeDirectSolidAngle);
HWY_EXPORT(Lanes);
HWY_EXPORT(TargetName);

int packetLanes() {
  return HWY_DYNAMIC_DISPATCH(Lanes)();
}

std::string packetTargetName() {
  return HWY_DYNAMIC_DISPATCH(TargetName)();
}

std::vector<std::string> availablePacketTargets() {
  std::vector<std::string> names;
  for (int64_t target : hwy::SupportedAndGeneratedTargets()) names.push_back(hwy::TargetName(target));
  return names;
}

bool forcePacketTarget(const std::string& name) {
  hwy::SetSupportedTargetsForTest(0);
  if (name.empty() || name == "auto") return true;
  for (int64_t target : hwy::SupportedAndGeneratedTargets())
    if (name == hwy::TargetName(target)) {
      hwy::SetSupportedTargetsForTest(target);
      return true;
    }
  return false;
}

void shadeDirectPacket(const PacketScene& scene, const PacketRays& rays, const PacketDraws& draws,
                       PacketRadiance& out) {
  if (scene.measure == LightMeasure::Area)
    HWY_DYNAMIC_DISPATCH(ShadeDirectArea)(scene, rays, draws, out);
  else
    HWY_DYNAMIC_DISPATCH(ShadeDirectSolidAngle)(scene, rays, draws, out);
}

}  // namespace penumbra
#endif
