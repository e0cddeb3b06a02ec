// Every sampler kind in lanes: each lane restarts its pixel sample's stream from its key and draws from
// it as Sampler::startPixelSample and Sampler::next2D do (independent: SplitMix64 hashes of key and
// sample index, PCG32's seeding, steps and XSH-RR output as pcg-cpp computes them; stratified: the same
// PCG32 jitter inside strata chosen by Kensler's hashed permutation; sobol and zsobol:
// BasicSobolStream's request hashes, index shuffle and Owen scrambles), in 64-bit integer lanes, so
// every draw is the scalar sampler's bit for bit.
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
#include "core/sampling/kensler_permutation.h"
#include "core/sampling/owen_scramble.h"
#include "core/sampling/sobol_matrices.h"
#include "core/sampling/sobol_stream.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using DU64 = hn::RebindToUnsigned<DD>;
using VU64 = hn::Vec<DU64>;

// Where a draw plan's calls put their two values: call 0 (the filter's) into filterU, call i into
// draws.draw[i - 1].
struct DrawOutputs {
  float (&filterU)[2][kMaxPacketLanes];
  PacketDraws& draws;
  float* at(int call, int c) const { return call == 0 ? filterU[c] : draws.draw[call - 1].u[c]; }
};

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

// Integer lane values below 2^52 as doubles, exactly: their bits under 2^52's exponent, minus 2^52.
HWY_INLINE VD exactDouble(VU64 v) {
  return hn::BitCast(DD(), hn::Or(v, setU64(0x4330000000000000ULL))) - setD(4503599627370496.0);
}

// Each lane's stream key: hashCombine of the seed's hash and the lane's word (pixelStreamKey,
// zsobolTileKey).
HWY_INLINE VU64 streamKeys(const PacketStreamStart& start) {
  return hashCombineLanes(setU64(start.seedHash), hn::LoadU(DU64(), start.word));
}

// bitsToUnitFloat (rng.h) of 32-bit lane values: the top 24 bits times 2^-24, exactly.
HWY_INLINE VF unitFloat(VU64 bits32) {
  return demote(exactDouble(hn::ShiftRight<8>(bits32)) * setD(0x1p-24));
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
    return unitFloat(rotated);
  }
};

// Each lane's `drawCount` draws (the filter's and the shading draws) of the independent sampler:
// PCG32 on the stream of the lane's key, started at the hash of key and sample index.
HWY_INLINE void independentDraws(const PacketStreamStart& start, int drawCount, const DrawOutputs& out) {
  const DF df;
  const VU64 key = streamKeys(start);
  PcgLanes rng(hashCombineLanes(key, setU64(start.pass)), key);
  for (int j = 0; j < drawCount; ++j)
    for (int c = 0; c < 2; ++c) hn::StoreU(rng.nextFloat(), df, out.at(j, c));
}

// The low 32 bits of each lane.
HWY_INLINE VU64 low32(VU64 v) {
  return hn::And(v, setU64(0xffffffffULL));
}

// x * c modulo 2^32 for 32-bit lane values.
HWY_INLINE VU64 mul32(VU64 x, VU64 c) {
#if HWY_TARGET == HWY_SCALAR
  return setU64(uint32_t(hn::GetLane(x) * hn::GetLane(c)));
#else
  const hn::Repartition<uint32_t, DU64> d32;
  return low32(hn::MulEven(hn::BitCast(d32, x), hn::BitCast(d32, c)));
#endif
}

// Exact x mod n and x / n (rounded down) of integer-valued doubles below 2^32, n >= 1: the double
// quotient's floor is exact there (the gap to the next integer, 1/n, is far above its rounding).
HWY_INLINE void divMod(VD x, double n, VD& quotient, VD& remainder) {
  quotient = hn::Floor(x / setD(n));
  remainder = x - quotient * setD(n);
}

// kenslerPermute (kensler_permutation.h) of index i with each lane's 32-bit key, each lane walking its
// cycle until it lands below n; the stratum as an exact double.
HWY_INLINE VD kenslerPermuteLanes(uint32_t i, uint32_t n, VU64 key) {
  const DU64 du;
  const hn::RebindToSigned<DU64> di;
  const VU64 mask = setU64(kenslerPermutationMask(n));
  const VU64 keyMultiplier = hn::Or(setU64(1), hn::ShiftRight<27>(key));
  VU64 v = setU64(i), landed = hn::Zero(du);
  auto walking = hn::FirstN(du, hn::Lanes(du));
  do {
    v = hn::Xor(v, key);
    v = mul32(v, setU64(0xe170893du));
    v = hn::Xor(v, hn::ShiftRight<16>(key));
    v = hn::Xor(v, hn::ShiftRight<4>(hn::And(v, mask)));
    v = hn::Xor(v, hn::ShiftRight<8>(key));
    v = mul32(v, setU64(0x0929eb3fu));
    v = hn::Xor(v, hn::ShiftRight<23>(key));
    v = hn::Xor(v, hn::ShiftRight<1>(hn::And(v, mask)));
    v = mul32(v, keyMultiplier);
    v = mul32(v, setU64(0x6935fa69u));
    v = hn::Xor(v, hn::ShiftRight<11>(hn::And(v, mask)));
    v = mul32(v, setU64(0x74dcb303u));
    v = hn::Xor(v, hn::ShiftRight<2>(hn::And(v, mask)));
    v = mul32(v, setU64(0x9e501cc3u));
    v = hn::Xor(v, hn::ShiftRight<2>(hn::And(v, mask)));
    v = mul32(v, setU64(0xc860a3dfu));
    v = hn::And(v, mask);
    v = hn::Xor(v, hn::ShiftRight<5>(v));
    // Values are below 2^32, so the signed comparison is the unsigned one.
    const auto below = hn::RebindMask(du, hn::BitCast(di, v) < hn::Set(di, int64_t(n)));
    landed = hn::IfThenElse(hn::And(walking, below), v, landed);
    walking = hn::AndNot(below, walking);
  } while (!hn::AllFalse(du, walking));
  VD quotient, stratum;
  divMod(exactDouble(low32(landed + key)), double(n), quotient, stratum);
  return stratum;
}

// jittered (sampler.cpp): (stratum + jitter) / strata, kept below 1.
HWY_INLINE VF jittered(VD stratum, VF jitter, float invStrata) {
  return hn::Min((demote(stratum) + jitter) * setF(invStrata), setF(kOneMinusEpsilon));
}

// Each lane's `drawCount` draws of the stratified sampler (Sampler::stratified2D): draw d's stratum of
// the gridSide^2 grid permuted by the hash of (key, epoch, d), jittered by the lane's PCG32 stream.
HWY_INLINE void stratifiedDraws(const PacketStreamStart& start, int drawCount, const DrawOutputs& out) {
  const DF df;
  const VU64 key = streamKeys(start);
  PcgLanes rng(hashCombineLanes(key, setU64(start.pass)), key);
  const uint32_t side = start.gridSide, strata = side * side;
  const uint64_t epoch = uint64_t(start.pass / strata) << 32;
  const float invSide = 1.f / static_cast<float>(side);
  for (int d = 0; d < drawCount; ++d) {
    const VU64 permutationKey = low32(hashCombineLanes(key, setU64(epoch | uint32_t(d))));
    const VD stratum = kenslerPermuteLanes(start.pass % strata, strata, permutationKey);
    VD row, column;
    divMod(stratum, double(side), row, column);
    const VF jx = rng.nextFloat();
    const VF jy = rng.nextFloat();
    hn::StoreU(jittered(column, jx, invSide), df, out.at(d, 0));
    hn::StoreU(jittered(row, jy, invSide), df, out.at(d, 1));
  }
}

// laineKarrasPermutation (owen_scramble.h) of 32-bit lane values.
HWY_INLINE VU64 laineKarras(VU64 x, VU64 seed) {
  x = low32(x + seed);
  x = hn::Xor(x, mul32(x, setU64(0x6c50b47cu)));
  x = hn::Xor(x, mul32(x, setU64(0xb82f1e52u)));
  x = hn::Xor(x, mul32(x, setU64(0xc7afe638u)));
  return hn::Xor(x, mul32(x, setU64(0x8d22f6e6u)));
}

// reverseBits32 (owen_scramble.h) of 32-bit lane values.
HWY_INLINE VU64 reverseBits32Lanes(VU64 x) {
  x = hn::Or(low32(hn::ShiftLeft<16>(x)), hn::ShiftRight<16>(x));
  x = hn::Or(hn::ShiftLeft<8>(hn::And(x, setU64(0x00ff00ffu))),
             hn::And(hn::ShiftRight<8>(x), setU64(0x00ff00ffu)));
  x = hn::Or(hn::ShiftLeft<4>(hn::And(x, setU64(0x0f0f0f0fu))),
             hn::And(hn::ShiftRight<4>(x), setU64(0x0f0f0f0fu)));
  x = hn::Or(hn::ShiftLeft<2>(hn::And(x, setU64(0x33333333u))),
             hn::And(hn::ShiftRight<2>(x), setU64(0x33333333u)));
  return hn::Or(hn::ShiftLeft<1>(hn::And(x, setU64(0x55555555u))),
                hn::And(hn::ShiftRight<1>(x), setU64(0x55555555u)));
}

// sobolPairDigits (sobol_matrices.h): one gather per byte of the bit-reversed index.
HWY_INLINE VU64 sobolPairDigitsLanes(VU64 reversedIndex) {
  const DU64 du;
  const hn::RebindToSigned<DU64> di;
  const uint64_t* table = &kSobolPairTables.byte[0][0];
  VU64 digits = hn::Zero(du);
  for (int b = 0; b < 4; ++b) {
    const VU64 byte = hn::And(hn::ShiftRightSame(reversedIndex, 8 * b), setU64(0xff)) + setU64(256u * b);
    digits = hn::Xor(digits, hn::GatherIndex(du, table, hn::BitCast(di, byte)));
  }
  return digits;
}

// Each lane's draws of the plan's calls from the `sobol` or `zsobol` sampler: BasicSobolStream's
// next2D() and array points (prepare, shuffled, setZSobolIndex, sobolPoint2D) in 64-bit lanes holding
// 32-bit values.
HWY_INLINE void sobolDraws(const PacketStreamStart& start, const PacketDrawPlan& plan,
                           const DrawOutputs& out) {
  const DF df;
  const DU64 du;
  HWY_ALIGN uint64_t tileCodes[kMaxPacketLanes];
  for (size_t k = 0; k < hn::Lanes(du); ++k) tileCodes[k] = start.reversedTileCode[k];
  const VU64 key = streamKeys(start), tileCode = hn::Load(du, tileCodes);
  // zsobol's index of (tile, sample) from the sample's bit-reversed index s: the tile code above m
  // bits, s's top m bits beside it, the rest XORed in after the shuffle.
  auto zsobolIndex = [&](uint32_t m, uint32_t reversedS, VU64& reversed, VU64& reversedXor) {
    const uint32_t top = zsobolSampleBits(m);
    reversed = hn::Or(hn::ShiftRightSame(tileCode, int(m)), setU64(reversedS & top));
    reversedXor = setU64(reversedS & ~top);
  };
  const bool zsobol = start.kind == SamplerKind::ZSobol;
  const uint32_t reversedPass = reverseBits32(start.pass);
  VU64 ownReversed = setU64(reversedPass), ownXor = hn::Zero(du);
  if (zsobol) zsobolIndex(start.log2Samples, reversedPass, ownReversed, ownXor);
  for (int i = 0; i < plan.count; ++i) {
    const SobolDrawCall& c = plan.calls[i];
    const VU64 hash = hashCombineLanes(key, setU64(plan.requests[i]));
    VU64 reversed = ownReversed, reversedXor = ownXor;
    if (c.n > 1) {
      const uint32_t reversedArray = reverseBits32(start.pass * c.n + c.j);
      if (zsobol)
        zsobolIndex(std::min(start.log2Samples + zsobolLog2Samples(c.n), kZSobolMaxLog2Samples),
                    reversedArray, reversed, reversedXor);
      else
        reversed = setU64(reversedArray), reversedXor = hn::Zero(du);
    }
    const VU64 index = hn::Xor(laineKarras(reversed, low32(hash)), reversedXor);
    const VU64 digits = sobolPairDigitsLanes(index);
    const VU64 x = laineKarras(low32(digits), hn::ShiftRight<32>(hash));
    const VU64 y = laineKarras(hn::ShiftRight<32>(digits),
                               hn::ShiftRight<32>(mul64(hash, setU64(0x9e3779b97f4a7c15ULL))));
    hn::StoreU(unitFloat(reverseBits32Lanes(x)), df, out.at(i, 0));
    hn::StoreU(unitFloat(reverseBits32Lanes(y)), df, out.at(i, 1));
  }
}

// Each lane's draws of the plan's calls from its sampler kind: the filter's into filterU, the
// shading draws into draws.draw.
HWY_INLINE void samplerDraws(const PacketStreamStart& start, const PacketDrawPlan& plan,
                             float (&filterU)[2][kMaxPacketLanes], PacketDraws& draws) {
  const DrawOutputs outputs{filterU, draws};
  switch (start.kind) {
    case SamplerKind::Independent:
      return independentDraws(start, plan.count, outputs);
    case SamplerKind::Stratified:
      return stratifiedDraws(start, plan.count, outputs);
    case SamplerKind::Sobol:
    case SamplerKind::ZSobol:
      return sobolDraws(start, plan, outputs);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#endif
