// The independent sampler in lanes: each lane restarts its pixel sample's stream and draws from it as
// Sampler::startPixelSample and Sampler::next2D do for SamplerKind::Independent (SplitMix64 hashes of
// seed, pixel and sample index; PCG32's seeding, steps and XSH-RR output, as pcg-cpp computes them),
// in 64-bit integer lanes, so every draw is the scalar sampler's bit for bit.
// Part of the packet kernels: included by packet_kernels.cpp once per instruction set (Highway's
// re-inclusion toggle below), inside that set's namespace.
#if defined(PENUMBRA_PACKET_SAMPLER_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PENUMBRA_PACKET_SAMPLER_INL_H_
#undef PENUMBRA_PACKET_SAMPLER_INL_H_
#else
#define PENUMBRA_PACKET_SAMPLER_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstdint>

#include "core/render/packet_kernels.h"
#include "core/render/packet_math-inl.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using DU64 = hn::RebindToUnsigned<DD>;
using VU64 = hn::Vec<DU64>;

HWY_INLINE VU64 setU64(uint64_t v) {
  return hn::Set(DU64(), v);
}

// a * b modulo 2^64 from 32 x 32 -> 64-bit products: Highway has no 64-bit lane multiply on x86.
HWY_INLINE VU64 mul64(VU64 a, VU64 b) {
#if HWY_TARGET == HWY_SCALAR
  return setU64(hn::GetLane(a) * hn::GetLane(b));
#else
  const hn::Repartition<uint32_t, DU64> d32;
  const VU64 low = hn::MulEven(hn::BitCast(d32, a), hn::BitCast(d32, b));
  const VU64 cross = hn::MulEven(hn::BitCast(d32, hn::ShiftRight<32>(a)), hn::BitCast(d32, b)) +
                     hn::MulEven(hn::BitCast(d32, a), hn::BitCast(d32, hn::ShiftRight<32>(b)));
  return low + hn::ShiftLeft<32>(cross);
#endif
}

// mix64 (rng.h): SplitMix64's finaliser.
HWY_INLINE VU64 mix64Lanes(VU64 x) {
  x = hn::Xor(x, hn::ShiftRight<30>(x));
  x = mul64(x, setU64(0xbf58476d1ce4e5b9ULL));
  x = hn::Xor(x, hn::ShiftRight<27>(x));
  x = mul64(x, setU64(0x94d049bb133111ebULL));
  return hn::Xor(x, hn::ShiftRight<31>(x));
}

// hashCombine (rng.h).
HWY_INLINE VU64 hashCombineLanes(VU64 a, VU64 b) {
  return mix64Lanes(hn::Xor(a, b + setU64(0x9e3779b97f4a7c15ULL)));
}

// pcg32 (pcg-cpp's setseq_xsh_rr_64_32): a 64-bit LCG on the stream `increment`, each draw the XSH-RR
// output of the state before the step.
struct PcgLanes {
  static constexpr uint64_t kMultiplier = 6364136223846793005ULL;
  VU64 increment, state;

  // pcg32(state, stream): the stream's odd increment, the state bumped once past state + increment.
  PcgLanes(VU64 seedState, VU64 stream)
      : increment(hn::Or(hn::ShiftLeft<1>(stream), setU64(1))),
        state(mul64(seedState + increment, setU64(kMultiplier)) + increment) {}

  // bitsToUnitFloat(pcg32()): the top 24 of the 32 output bits times 2^-24.
  HWY_INLINE VF nextFloat() {
    const VU64 old = state;
    state = mul64(state, setU64(kMultiplier)) + increment;
    const VU64 mask32 = setU64(0xffffffffULL);
    const VU64 rotation = hn::ShiftRight<59>(old);
    const VU64 bits = hn::And(hn::ShiftRight<27>(hn::Xor(old, hn::ShiftRight<18>(old))), mask32);
    const VU64 rotated =
        hn::Or(bits >> rotation, hn::And(bits << hn::And(setU64(32) - rotation, setU64(31)), mask32));
    // An integer below 2^52 as a double, exactly: its bits under 2^52's exponent, minus 2^52.
    const DD dd;
    const VD top24 = hn::BitCast(dd, hn::Or(hn::ShiftRight<8>(rotated), setU64(0x4330000000000000ULL))) -
                     setD(4503599627370496.0);
    return demote(top24 * setD(0x1p-24));
  }
};

// Each lane's filter draw and `drawCount` shading draws of the independent sampler, for pixels x0 ..
// x0 + count - 1 of row y (lanes past `count` repeat the last) at sample index `pass`: what the row
// loop's Sampler::startPixelSample, next2D() and next2D(j, n[, k, m]) return for that kind.
HWY_INLINE void independentDraws(uint64_t seedHash, int x0, int y, int count, uint32_t pass, int drawCount,
                                 float (&filterU)[2][kMaxPacketLanes], PacketDraws& draws) {
  const DF df;
  const DU64 du;
  HWY_ALIGN uint64_t packed[kMaxPacketLanes];
  for (size_t k = 0; k < hn::Lanes(du); ++k)
    packed[k] = (uint64_t(uint32_t(x0 + std::min(int(k), count - 1))) << 32) | uint32_t(y);
  const VU64 pixelKey = hashCombineLanes(setU64(seedHash), hn::Load(du, packed));
  PcgLanes rng(hashCombineLanes(pixelKey, setU64(pass)), pixelKey);
  for (int c = 0; c < 2; ++c) hn::StoreU(rng.nextFloat(), df, filterU[c]);
  for (int j = 0; j < drawCount; ++j)
    for (int c = 0; c < 2; ++c) hn::StoreU(rng.nextFloat(), df, draws.u[j][c]);
}

}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#endif
