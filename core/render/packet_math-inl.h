// Lane-wise math of the packet kernels: float and double vectors of one lane count, 3-vectors of
// them, and the scalar helpers they mirror (glm::dot, std::max, sinCosTurns, Frame, the warps).
// Part of the packet kernels: included by packet_kernels.cpp once per instruction set (Highway's
// re-inclusion toggle below), inside that set's namespace.
#if defined(PENUMBRA_PACKET_MATH_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PENUMBRA_PACKET_MATH_INL_H_
#undef PENUMBRA_PACKET_MATH_INL_H_
#else
#define PENUMBRA_PACKET_MATH_INL_H_
#endif

#include <hwy/highway.h>

#include "core/math/float_util.h"
#include "core/math/portable_atan2.h"
#include "core/math/sincos_turns.h"
#include "core/math/vec.h"
#include "core/render/packet_kernels.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
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
// A light pick's outputs: light[k] the picked light's index where `some` (else -1) and pmf[k] its
// probability (else 0).
HWY_INLINE void storeLightPicks(MD some, VD lightIndex, VD probability, float* light, double* pmf) {
  const DD dd;
  HWY_ALIGN double lights[kMaxPacketLanes];
  hn::Store(hn::IfThenElse(some, lightIndex, setD(-1.0)), dd, lights);
  hn::StoreU(hn::IfThenElseZero(some, probability), dd, pmf);
  for (size_t k = 0; k < hn::Lanes(dd); ++k) light[k] = float(lights[k]);
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
// glm::cross.
template <class V3>
HWY_INLINE V3 cross(const V3& x, const V3& y) {
  return {x.y * y.z - y.y * x.z, x.z * y.x - y.z * x.x, x.x * y.y - y.x * x.y};
}
template <class V3, class M>
HWY_INLINE V3 select(M m, const V3& a, const V3& b) {
  return {hn::IfThenElse(m, a.x, b.x), hn::IfThenElse(m, a.y, b.y), hn::IfThenElse(m, a.z, b.z)};
}
// glm::normalize: v · (1 / sqrt(v · v)).
template <class V3>
HWY_INLINE V3 normalized(const V3& v) {
  const auto inv = hn::Set(hn::DFromV<decltype(v.x)>(), 1) / hn::Sqrt(dot(v, v));
  return {v.x * inv, v.y * inv, v.z * inv};
}

// libm's fn(x) (and fn(x, y)) in the lanes of m (0 elsewhere), lane by lane: for exp, log1p, sin, cos
// and atan2, which no lane function rounds exactly as libm does.
template <class V, class M, class Fn>
HWY_INLINE V libmLanes(M m, V x, Fn fn) {
  const hn::DFromV<V> d;
  using T = hn::TFromV<V>;
  HWY_ALIGN T v[kMaxPacketLanes], on[kMaxPacketLanes];
  hn::Store(x, d, v);
  hn::Store(hn::IfThenElseZero(m, hn::Set(d, T(1))), d, on);
  for (size_t k = 0; k < hn::Lanes(d); ++k) v[k] = on[k] != T(0) ? fn(v[k]) : T(0);
  return hn::Load(d, v);
}
template <class V, class M, class Fn>
HWY_INLINE V libmLanes(M m, V x, V y, Fn fn) {
  const hn::DFromV<V> d;
  using T = hn::TFromV<V>;
  HWY_ALIGN T v[kMaxPacketLanes], w[kMaxPacketLanes], on[kMaxPacketLanes];
  hn::Store(x, d, v);
  hn::Store(y, d, w);
  hn::Store(hn::IfThenElseZero(m, hn::Set(d, T(1))), d, on);
  for (size_t k = 0; k < hn::Lanes(d); ++k) v[k] = on[k] != T(0) ? fn(v[k], w[k]) : T(0);
  return hn::Load(d, v);
}

// std::max(a, b) and glm::max(a, b): (a < b) ? b : a, NaN in a kept.
HWY_INLINE VF maxOf(VF a, VF b) {
  return hn::IfThenElse(a < b, b, a);
}
// v · f per component (glm's vector times scalar, and scalar times vector).
template <class V3, class V>
HWY_INLINE V3 scaled(const V3& v, V f) {
  return {v.x * f, v.y * f, v.z * f};
}
template <class V3>
HWY_INLINE V3 plus(const V3& a, const V3& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class V3>
HWY_INLINE V3 minus(const V3& a, const V3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
// a · b per component (Color3's product).
HWY_INLINE V3F times(const V3F& a, const V3F& b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}

// maxAbsComponent.
HWY_INLINE VF maxAbs(const V3F& v) {
  return maxOf(hn::Abs(v.x), maxOf(hn::Abs(v.y), hn::Abs(v.z)));
}

// sinCosQuarterPi (core/math/sincos_turns.h): sin and cos of |x| <= π/4.
HWY_INLINE void sinCosQuarterPi(VF x, VF& s, VF& c) {
  using K = SinCosCoefficients;
  const VF x2 = x * x;
  s = x + x * x2 * (setF(K::kSin1) + x2 * (setF(K::kSin2) + x2 * setF(K::kSin3)));
  c = setF(1.f) - setF(0.5f) * x2 + x2 * x2 * (setF(K::kCos1) + x2 * (setF(K::kCos2) + x2 * setF(K::kCos3)));
}

// portableAtan2 (core/math/portable_atan2.h) in every lane, bit for bit; std::atan2 in the lanes of m
// with a non-finite argument.
HWY_INLINE VD portableAtan2Lanes(MD m, VD y, VD x) {
  using K = PortableAtan2;
  const DD dd;
  const VD zero = hn::Zero(dd), one = setD(1.0);
  const VD ax = hn::Abs(x), ay = hn::Abs(y);
  const MD swap = ay > ax;
  const VD num = hn::IfThenElse(swap, ax, ay), den = hn::IfThenElse(swap, ay, ax);
  const MD reduced = num > setD(K::kTanPiOver8) * den;
  VD z = hn::IfThenElse(reduced, (num - den) / (num + den), num / den);
  z = hn::IfThenElseZero(den > zero, z);
  const VD s = z * z;
  VD p = setD(K::kP[0]);
  for (int i = 1; i < 11; ++i) p = p * s + setD(K::kP[i]);
  const VD tail = z * (s * p);
  VD high = hn::IfThenElseZero(reduced, setD(K::kPiOver4)),
     low = hn::IfThenElseZero(reduced, setD(K::kPiOver4Low));
  VD sign = one;
  high = hn::IfThenElse(swap, setD(K::kPiOver2) - high, high);
  low = hn::IfThenElse(swap, setD(K::kPiOver2Low) - low, low);
  sign = hn::IfThenElse(swap, hn::Neg(sign), sign);
  const MD negativeX = hn::CopySign(one, x) < zero;
  high = hn::IfThenElse(negativeX, setD(K::kPi) - high, high);
  low = hn::IfThenElse(negativeX, setD(K::kPiLow) - low, low);
  sign = hn::IfThenElse(negativeX, hn::Neg(sign), sign);
  const VD r = hn::CopySign(high + (sign * z + (low + sign * tail)), y);
  const MD special = hn::AndNot(hn::And(hn::IsFinite(x), hn::IsFinite(y)), m);
  if (HWY_LIKELY(hn::AllFalse(dd, special))) return r;
  return hn::IfThenElse(special,
                        libmLanes(special, y, x, [](double a, double b) { return std::atan2(a, b); }), r);
}

// sinCosTurns (core/math/sincos_turns.h).
HWY_INLINE void sinCosTurns(VF turns, VF& sinOut, VF& cosOut) {
  const DF df;
  const VF quarters = setF(4.f) * turns;
  const VF bias = setF(SinCosCoefficients::kRoundingBias);
  const VF q = hn::IfThenElse(hn::Abs(quarters) < setF(0x1p22f), (quarters + bias) - bias, quarters);
  VF s, c;
  sinCosQuarterPi((quarters - q) * setF(kPiOver2), s, c);
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

// std::sqrt(std::max(x, 0.f)) (safeSqrt): NaN stays NaN as there.
HWY_INLINE VF safeSqrt(VF x) {
  const VF zero = hn::Zero(DF());
  return hn::Sqrt(hn::IfThenElse(x < zero, zero, x));
}

// directionFromOneMinusCos (core/sampling/warp_util.h): 1 − cos θ = w, azimuth 2π·u.
HWY_INLINE V3F directionFromOneMinusCos(VF w, VF u) {
  const VF sinTheta = safeSqrt(w * (setF(2.f) - w));
  VF sinPhi, cosPhi;
  sinCosTurns(u, sinPhi, cosPhi);
  return {sinTheta * cosPhi, sinTheta * sinPhi, setF(1.f) - w};
}

// concentricPoint (core/sampling/warp_util.h): the concentric disk's point (x, y) of (u0, u1), and rho.
struct DiskPointF {
  VF x, y, rho;
};
HWY_INLINE DiskPointF concentricPoint(VF u0, VF u1) {
  const VF eps = setF(0x1p-24f);
  const VF a = (setF(2.f) * u0 - setF(1.f)) + eps, b = (setF(2.f) * u1 - setF(1.f)) + eps;
  const MF aDominant = hn::Abs(a) > hn::Abs(b);
  const VF r = hn::IfThenElse(aDominant, a, b);
  const VF zero = hn::Zero(DF());
  const MF centre = r == zero;  // a == b == 0: the point (0, 0) with rho 0
  VF s, c;
  sinCosQuarterPi(setF(kPiOver4) * (hn::IfThenElse(aDominant, b, a) / r), s, c);
  return {hn::IfThenElseZero(hn::Not(centre), r * hn::IfThenElse(aDominant, c, s)),
          hn::IfThenElseZero(hn::Not(centre), r * hn::IfThenElse(aDominant, s, c)),
          hn::IfThenElseZero(hn::Not(centre), hn::Abs(r))};
}

// Warp::squareToCosineHemisphere through concentricPoint.
HWY_INLINE V3F squareToCosineHemisphere(VF u0, VF u1) {
  const DiskPointF d = concentricPoint(u0, u1);
  return {d.x, d.y, safeSqrt((setF(1.f) - d.rho) * (setF(1.f) + d.rho))};
}

// Frame (core/math/frame.h): Duff et al.'s basis about unit n, and toWorld.
struct FrameF {
  V3F s, t, n;
};
HWY_INLINE FrameF frameAbout(const V3F& n) {
  const VF sign = hn::CopySign(setF(1.f), n.z);
  const VF a = setF(-1.f) / (sign + n.z);
  const VF b = n.x * n.y * a;
  return {{setF(1.f) + sign * n.x * n.x * a, sign * b, hn::Neg(sign) * n.x},
          {b, sign + n.y * n.y * a, hn::Neg(n.y)},
          n};
}
HWY_INLINE V3F toWorld(const FrameF& f, const V3F& v) {
  return {f.s.x * v.x + f.t.x * v.y + f.n.x * v.z, f.s.y * v.x + f.t.y * v.y + f.n.y * v.z,
          f.s.z * v.x + f.t.z * v.y + f.n.z * v.z};
}

// offsetRayOrigin (core/math/float_util.h): p moved off the surface along ng, towards w's side.
HWY_INLINE V3F offsetRayOrigin(const V3F& p, const V3F& ng, VF scale, const V3F& w) {
  const VF d = setF(kRayOffsetScale) * scale;
  const VF signedD = hn::IfThenElse(dot(w, ng) < hn::Zero(DF()), hn::Neg(d), d);
  return {p.x + ng.x * signedD, p.y + ng.y * signedD, p.z + ng.z * signedD};
}

// isValidRadiance (float_util.h): every channel non-negative and their sum finite.
HWY_INLINE MF validRadiance(const V3F& L) {
  const VF zero = hn::Zero(DF());
  const MF nonNegative = hn::And(L.x >= zero, hn::And(L.y >= zero, L.z >= zero));
  return hn::And(nonNegative, hn::Abs(L.x + L.y + L.z) < setF(INFINITY));
}

}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#endif
