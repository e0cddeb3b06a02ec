// The `zsobol` sampler: one Owen-scrambled Sobol' sequence shared by the whole image, pixel p taking
// the indices of its Morton code (Ahmed and Wonka 2020, "Screen-space blue-noise diffusion of Monte
// Carlo sampling error via hierarchical ordering of pixels"; pbrt-v4's ZSobolSampler). With
// 2^m = the run's sample count rounded up to a power of two, pixel p's first 2^m samples are the
// indices (morton(p) << m) + [0, 2^m), shuffled per request by a nested uniform scramble, which maps
// every aligned 2^j x 2^j pixel tile onto one aligned block of the sequence: at 2^m samples every
// tile's samples together form a (0, 2j + m, 2)-net, so the errors of neighbouring pixels cancel
// (their error is spread like blue noise). Ahmed and Wonka permute base-4 digits; this base-2
// scramble also maps tiles onto blocks and costs one hash instead of one per digit.
//
// Progressive: for every k, a pixel's first 2^k samples form a (0,2)-net in every 2-D request. For
// sample indices s >= 2^m, the shuffled index is XORed with s's bits above m, so the pixel keeps
// getting nets (its first 2^k indices still differ in their low k bits) but neighbours no longer
// share one net: the blue-noise property holds at 2^m samples per pixel.
//
// Limits: index bits above 32 are not in the matrices, so the Morton code's bits above 32 - m choose
// the value scrambles instead (tiles of 2^((32 - m) / 2) pixels are randomised independently of each
// other); m <= kZSobolMaxLog2Samples; otherwise as for `sobol`.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>

#include "core/math/vec.h"
#include "core/sampling/morton.h"
#include "core/sampling/rng.h"
#include "core/sampling/sobol_points.h"

namespace penumbra {

// Keeps at least 12 index bits for the Morton code (tiles of 64 x 64 pixels share one sequence).
inline constexpr uint32_t kZSobolMaxLog2Samples = 20;

template <class Randomizer>
class BasicZSobolSampler {
 public:
  // sampleCount: the run's samples per pixel (the count at which the error is blue noise).
  BasicZSobolSampler(uint32_t sampleCount, uint64_t seed)
      : seed_(seed),
        seedHash_(mix64(seed)),
        log2Samples_(std::min<uint32_t>(std::bit_width(std::max<uint32_t>(sampleCount, 1) - 1),
                                        kZSobolMaxLog2Samples)),
        sampleMask_((1u << log2Samples_) - 1) {
    startPixelSample(IVec2(0), 0);
  }

  void startPixelSample(IVec2 pixel, uint32_t sampleIndex) {
    const uint64_t morton = encodeMorton2(static_cast<uint32_t>(pixel.x), static_cast<uint32_t>(pixel.y));
    const uint32_t mortonBits = 32 - log2Samples_;
    key_ = hashCombine(seedHash_, morton >> mortonBits);
    const auto tileCode = static_cast<uint32_t>(morton & ((uint64_t{1} << mortonBits) - 1));
    reversedIndex_ = reverseBits32((tileCode << log2Samples_) | (sampleIndex & sampleMask_));
    reversedIndexXor_ = reverseBits32(sampleIndex & ~sampleMask_);
    request_ = 0;
  }

  // Uniform in [0, 1): never returns 1.0.
  float next1D() {
    const uint64_t h = requestHash(key_, request_++);
    return sobolPoint1D<Randomizer>(index(h), h);
  }
  Vec2 next2D() {
    const uint64_t h = requestHash(key_, request_++);
    return sobolPoint2D<Randomizer>(index(h), h);
  }

  uint64_t seed() const { return seed_; }
  // log2 of the count at which neighbouring pixels share nets.
  uint32_t log2Samples() const { return log2Samples_; }

 private:
  uint32_t index(uint64_t requestHash) const {
    return Randomizer::shuffledReversedIndex(reversedIndex_, static_cast<uint32_t>(requestHash)) ^
           reversedIndexXor_;
  }

  uint64_t seed_ = 0;
  uint64_t seedHash_ = 0;
  uint32_t log2Samples_ = 0;
  uint32_t sampleMask_ = 0;
  uint64_t key_ = 0;  // hash of (seed, Morton code bits above the index)
  uint32_t reversedIndex_ = 0;
  uint32_t reversedIndexXor_ = 0;  // sample index bits above the tile net, bit-reversed
  uint32_t request_ = 0;
};

using ZSobolSampler = BasicZSobolSampler<OwenScrambling>;

}  // namespace penumbra
