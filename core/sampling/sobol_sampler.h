// The `sobol` sampler: per pixel, an Owen-scrambled Sobol' sequence with the index shuffled per pixel
// (Burley 2020; pbrt-v4's padded Sobol' sampler), decorrelated between pixels by seeding every
// shuffle and scramble from (seed, pixel, request). Progressive: for every k, the first 2^k samples
// of a pixel form a (0,2)-net in every 2-D request and a (0,1)-net in every 1-D request, whatever
// the final count. A stream is a pure function of (seed, pixel, sample index).
//
// Limits: any number of requests (each uses its own padding of dimensions 0 and 1); sample indices
// are 32-bit; values have 24 bits (bitsToUnitFloat), so nets of up to 2^24 points are exact.
#pragma once

#include <cstdint>

#include "core/math/vec.h"
#include "core/sampling/rng.h"
#include "core/sampling/sobol_points.h"

namespace penumbra {

template <class Randomizer>
class BasicSobolSampler {
 public:
  explicit BasicSobolSampler(uint64_t seed) : seed_(seed), seedHash_(mix64(seed)) {
    startPixelSample(IVec2(0), 0);
  }

  // Cheap: one hash and one bit reversal per camera sample.
  void startPixelSample(IVec2 pixel, uint32_t sampleIndex) {
    const uint64_t packed =
        (static_cast<uint64_t>(static_cast<uint32_t>(pixel.x)) << 32) | static_cast<uint32_t>(pixel.y);
    key_ = hashCombine(seedHash_, packed);
    reversedIndex_ = reverseBits32(sampleIndex);
    request_ = 0;
  }

  // Uniform in [0, 1): never returns 1.0.
  float next1D() {
    const uint64_t h = requestHash(key_, request_++);
    return sobolPoint1D<Randomizer>(
        Randomizer::shuffledReversedIndex(reversedIndex_, static_cast<uint32_t>(h)), h);
  }
  Vec2 next2D() {
    const uint64_t h = requestHash(key_, request_++);
    return sobolPoint2D<Randomizer>(
        Randomizer::shuffledReversedIndex(reversedIndex_, static_cast<uint32_t>(h)), h);
  }

  uint64_t seed() const { return seed_; }

 private:
  uint64_t seed_ = 0;
  uint64_t seedHash_ = 0;
  uint64_t key_ = 0;            // hash of (seed, pixel)
  uint32_t reversedIndex_ = 0;  // the sample index, bit-reversed for the nested shuffle
  uint32_t request_ = 0;        // next1D/next2D calls since startPixelSample
};

using SobolSampler = BasicSobolSampler<OwenScrambling>;

}  // namespace penumbra
