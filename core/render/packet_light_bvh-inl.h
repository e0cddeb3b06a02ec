// The light BVH's pick in lanes (LightBvh::pick with lightBvhImportance, mirrored operation by operation
// in double): each lane walks the tree from the root to its own leaf, the nodes' data gathered per lane
// from PacketLightBvh, until every lane has reached a leaf or picked nothing.
// Part of the packet kernels: included by packet_kernels.cpp once per instruction set (Highway's
// re-inclusion toggle below), inside that set's namespace.
#if defined(PENUMBRA_PACKET_LIGHT_BVH_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PENUMBRA_PACKET_LIGHT_BVH_INL_H_
#undef PENUMBRA_PACKET_LIGHT_BVH_INL_H_
#else
#define PENUMBRA_PACKET_LIGHT_BVH_INL_H_
#endif

#include <hwy/highway.h>

#include "core/render/packet_math-inl.h"
#include "core/render/packet_scene.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using DI64 = hn::RebindToSigned<DD>;
using VI64 = hn::Vec<DI64>;

// Each lane's value of a node field for the lanes' nodes.
HWY_INLINE VD gatherNodes(const std::vector<double>& field, VI64 node) {
  return hn::GatherIndex(DD(), field.data(), node);
}

// std::min(v, hi): (hi < v) ? hi : v, NaN kept.
HWY_INLINE VD minOf(VD v, VD hi) {
  return hn::IfThenElse(hi < v, hi, v);
}

// lightBvhImportance of each lane's node `node` for shading point p with shading normal n (double).
HWY_INLINE VD bvhImportance(const PacketLightBvh& bvh, VI64 node, const V3D& p, const V3D& n,
                            MD nonzeroNormal) {
  const DD dd;
  const VD zero = hn::Zero(dd), one = setD(1.0);
  const VD maxImportance = setD(1e300);
  auto gather = [&](const std::vector<double>& field) { return gatherNodes(field, node); };
  const VD power = gather(bvh.power), r2 = gather(bvh.radius2);
  const V3D toCentre{gather(bvh.centreX) - p.x, gather(bvh.centreY) - p.y, gather(bvh.centreZ) - p.z};
  const VD d2 = dot(toCentre, toCentre);
  // p inside the bounding sphere: power / max(r², 1e-300).
  const VD inside = minOf(power / hn::IfThenElse(r2 < setD(1e-300), setD(1e-300), r2), maxImportance);
  const VD sin2b = r2 / d2;
  const VD cosb = hn::Sqrt(one - sin2b), sinb = hn::Sqrt(sin2b);
  const VD d = hn::Sqrt(d2);
  // std::max(0.0, v): NaN goes to 0 as there.
  auto atLeastZeroD = [&](VD v) { return hn::IfThenElse(zero < v, v, zero); };
  // The receiver's cosine over the bounds.
  const VD cosi = dot(n, toCentre) / d;
  const MD tilted = hn::And(nonzeroNormal, cosi < cosb);
  const VD sini = hn::Sqrt(atLeastZeroD(one - cosi * cosi));
  const VD cosReceiver = cosi * cosb + sini * sinb;
  MD dark = hn::And(tilted, hn::Not(cosReceiver > zero));
  VD cosBound = hn::IfThenElse(tilted, cosReceiver, one);
  // The emitters' cosine towards p over the node's cone.
  const VD coso = gather(bvh.cosCone);
  const V3D axis{gather(bvh.axisX), gather(bvh.axisY), gather(bvh.axisZ)};
  const VD cosw = hn::Neg(dot(axis, toCentre)) / d;
  const VD sinw = hn::Sqrt(atLeastZeroD(one - cosw * cosw));
  const VD sino = hn::Sqrt(atLeastZeroD(one - coso * coso));
  const VD cosx = cosw * coso + sinw * sino, sinx = sinw * coso - cosw * sino;
  const MD bounded = hn::And(hn::And(coso > setD(-1.0), cosw < coso), cosx < cosb);
  const VD cosEmit = cosx * cosb + sinx * sinb;
  dark = hn::Or(dark, hn::And(bounded, hn::Not(cosEmit > zero)));
  cosBound = hn::IfThenElse(bounded, cosBound * cosEmit, cosBound);
  const VD outside = minOf(power * cosBound / d2, maxImportance);
  const VD importance = hn::IfThenElse(d2 <= r2, inside, hn::IfThenElseZero(hn::Not(dark), outside));
  return hn::IfThenElseZero(power > zero, importance);
}

// LightBvh::pick of each lane of `active` at its shading point p with shading normal n, from the two
// floats of its pick draw (u0 + u1 2^-24): light[k] the light's index (-1 where nothing is picked, and
// in inactive lanes) and pmf[k] its probability (0 there).
HWY_INLINE void pickBvhLights(const PacketLightBvh& bvh, const V3F& pF, const V3F& nF, VF u0, VF u1,
                              MF active, float* light, double* pmf) {
  const DD dd;
  const DI64 di;
  const VD zero = hn::Zero(dd);
  if (bvh.power.empty())  // no area lights: nothing is picked
    return storeLightPicks(hn::FirstN(dd, 0), zero, zero, light, pmf);
  const V3D p = promote(pF), n = promote(nF);
  const MD nonzeroNormal = hn::Or(hn::Or(n.x != zero, n.y != zero), n.z != zero);
  VI64 index = hn::Zero(di);
  MD walking = hn::And(toD(active), bvhImportance(bvh, index, p, n, nonzeroNormal) > zero);
  MD picked = walking;
  VD probability = setD(1.0);
  VD u = promote(u0) + promote(u1) * setD(0x1p-24);
  walking = hn::AndNot(gatherNodes(bvh.leaf, index) != zero, walking);
  while (!hn::AllFalse(dd, walking)) {
    // childProbabilities: the two children's importance, or their power where neither can reach p.
    // Lanes done walk the root's children alongside (their leaf's neighbours may not exist).
    const VI64 at = hn::IfThenElseZero(hn::RebindMask(di, walking), index);
    const VI64 first = at + hn::Set(di, 1);
    const VI64 second = hn::ConvertTo(di, gatherNodes(bvh.child, at));
    VD ia = bvhImportance(bvh, first, p, n, nonzeroNormal),
       ib = bvhImportance(bvh, second, p, n, nonzeroNormal);
    const MD unreachable = hn::Not(ia + ib > zero);
    ia = hn::IfThenElse(unreachable, gatherNodes(bvh.power, first), ia);
    ib = hn::IfThenElse(unreachable, gatherNodes(bvh.power, second), ib);
    const VD sum = ia + ib;
    const MD some = sum > zero;
    const VD pa = hn::IfThenElseZero(some, ia / sum), pb = hn::IfThenElseZero(some, ib / sum);
    const MD takeFirst = u < pa;
    const MD takeSecond = hn::AndNot(takeFirst, walking);
    const MD none = hn::And(takeSecond, hn::Not(pb > zero));
    picked = hn::AndNot(none, picked);
    walking = hn::AndNot(none, walking);
    const MD toFirst = hn::And(walking, takeFirst), toSecond = hn::AndNot(takeFirst, walking);
    index = hn::IfThenElse(hn::RebindMask(di, toFirst), first,
                           hn::IfThenElse(hn::RebindMask(di, toSecond), second, index));
    probability =
        hn::IfThenElse(toFirst, probability * pa, hn::IfThenElse(toSecond, probability * pb, probability));
    const VD next = hn::IfThenElse(toFirst, u / pa, (u - pa) / pb);
    u = hn::IfThenElse(walking, minOf(next, setD(0x1.fffffffffffffp-1)), u);
    walking = hn::AndNot(gatherNodes(bvh.leaf, index) != zero, walking);
  }
  const VD lightIndex = gatherNodes(bvh.child, index);
  storeLightPicks(hn::And(picked, probability > zero), lightIndex, probability, light, pmf);
}

}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#endif
