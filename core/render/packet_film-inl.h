// Film accumulation in lanes: Film::add of each lane's weighted radiance, after the row loop's
// isValidRadiance check, with the products and squares computed in lanes and the pixel sums added in
// the scalar loop's order.
// Part of the packet kernels: included by packet_kernels.cpp once per instruction set (Highway's
// re-inclusion toggle below), inside that set's namespace.
#if defined(PENUMBRA_PACKET_FILM_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PENUMBRA_PACKET_FILM_INL_H_
#undef PENUMBRA_PACKET_FILM_INL_H_
#else
#define PENUMBRA_PACKET_FILM_INL_H_
#endif

#include <hwy/highway.h>

#include <cstdint>

#include "core/render/packet_kernels.h"
#include "core/render/packet_math-inl.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Adds lane k's radiance times weight[k] to the 6 sums at sums + 6 k (r, g, b, r^2, g^2, b^2, as
// Film::add), for the first `count` lanes whose radiance is valid; returns how many of them were not
// (NaN, Inf or negative: counted, nothing added).
HWY_INLINE uint32_t filmAdd(const PacketRadiance& radiance, const float (&weight)[kMaxPacketLanes], int count,
                            double* sums) {
  const DF df;
  const DD dd;
  const V3F L = {hn::LoadU(df, radiance.L[0]), hn::LoadU(df, radiance.L[1]), hn::LoadU(df, radiance.L[2])};
  const MF valid = validRadiance(L);
  const VF w = hn::LoadU(df, weight);
  const V3D value = promote(V3F{L.x * w, L.y * w, L.z * w});
  // Lane k's six terms at terms[c][k], in Film::add's order.
  HWY_ALIGN double terms[6][kMaxPacketLanes];
  hn::Store(value.x, dd, terms[0]);
  hn::Store(value.y, dd, terms[1]);
  hn::Store(value.z, dd, terms[2]);
  hn::Store(value.x * value.x, dd, terms[3]);
  hn::Store(value.y * value.y, dd, terms[4]);
  hn::Store(value.z * value.z, dd, terms[5]);
  HWY_ALIGN uint8_t validBits[8] = {};
  hn::StoreMaskBits(df, valid, validBits);
  uint32_t invalid = 0;
  for (int k = 0; k < count; ++k) {
    if (!(validBits[k / 8] >> (k % 8) & 1)) {
      ++invalid;
      continue;
    }
    double* s = sums + 6 * k;
    for (int c = 0; c < 6; ++c) s[c] += terms[c][k];
  }
  return invalid;
}

}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#endif
