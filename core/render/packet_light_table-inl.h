// Uniform and power light selection in lanes: AliasTable::sample and pmf mirrored in double on
// PacketLightTable, each lane reading its own bin.
// Part of the packet kernels: included by packet_kernels.cpp once per instruction set (Highway's
// re-inclusion toggle below), inside that set's namespace.
#if defined(PENUMBRA_PACKET_LIGHT_TABLE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PENUMBRA_PACKET_LIGHT_TABLE_INL_H_
#undef PENUMBRA_PACKET_LIGHT_TABLE_INL_H_
#else
#define PENUMBRA_PACKET_LIGHT_TABLE_INL_H_
#endif

#include <hwy/highway.h>

#include "core/render/packet_math-inl.h"
#include "core/render/packet_scene.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// UniformLightSelection::pick or PowerLightSelection::pick of each lane of `active`, from the two
// floats of its pick draw (u0 + u1 2^-24): light[k] the light's index (-1 where nothing is picked, and
// in inactive lanes) and pmf[k] its probability (0 there).
HWY_INLINE void pickTableLights(const PacketLightTable& table, VF u0, VF u1, MF active, float* light,
                                double* pmf) {
  const DD dd;
  const hn::RebindToSigned<DD> di;
  const size_t n = table.pmf.size();
  if (n == 0)  // no area lights: nothing is picked
    return storeLightPicks(hn::FirstN(dd, 0), hn::Zero(dd), hn::Zero(dd), light, pmf);
  // AliasTable::sample: the bin static_cast<uint32_t>(u n) (truncation; u n ≥ 0), the last one where u
  // rounds up to 1, then its own light or its alias by the fraction left.
  const VD u = promote(u0) + promote(u1) * setD(0x1p-24);
  const VD x = u * setD(double(n));
  const VD last = setD(double(n - 1));
  VD bin = hn::Trunc(x);
  bin = hn::IfThenElse(bin > last, last, bin);
  const auto index = hn::ConvertTo(di, bin);
  const VD keep = hn::GatherIndex(dd, table.keep.data(), index);
  const VD alias = hn::GatherIndex(dd, table.alias.data(), index);
  const VD picked = hn::IfThenElse(x - bin < keep, bin, alias);
  const VD probability = hn::GatherIndex(dd, table.pmf.data(), hn::ConvertTo(di, picked));
  // The estimator's `pick.pmf > 0` test: a light of no power that an alias still reaches adds nothing.
  storeLightPicks(hn::And(toD(active), probability > hn::Zero(dd)), picked, probability, light, pmf);
}

}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#endif
