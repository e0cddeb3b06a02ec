// The `sobol` and `zsobol` streams (core/sampling/sobol_stream.h) as stand-alone samplers with the
// Sampler interface, for tests with other randomisations and for benchmarks.
#pragma once

#include <cstdint>

#include "core/math/vec.h"
#include "core/sampling/rng.h"
#include "core/sampling/sobol_stream.h"

namespace penumbra {

template <class Randomizer>
class BasicSobolSampler {
 public:
  explicit BasicSobolSampler(uint64_t seed) : seed_(seed), seedHash_(mix64(seed)) {
    startPixelSample(IVec2(0), 0);
  }
  void startPixelSample(IVec2 pixel, uint32_t sampleIndex) {
    stream_.startSobol(seedHash_, pixel, sampleIndex);
  }
  float next1D() { return stream_.next1D(); }
  Vec2 next2D() { return stream_.next2D(); }
  Vec2 next2D(uint32_t j, uint32_t n) { return stream_.next2D(j, n); }
  Vec2 next2D(uint32_t j, uint32_t n, uint32_t k, uint32_t m) { return stream_.next2D(j, n, k, m); }
  uint64_t seed() const { return seed_; }

 private:
  uint64_t seed_ = 0, seedHash_ = 0;
  BasicSobolStream<Randomizer> stream_;
};

template <class Randomizer>
class BasicZSobolSampler {
 public:
  // sampleCount: the run's samples per pixel (the count at which the error is blue noise).
  BasicZSobolSampler(uint32_t sampleCount, uint64_t seed)
      : seed_(seed), seedHash_(mix64(seed)), log2Samples_(zsobolLog2Samples(sampleCount)) {
    startPixelSample(IVec2(0), 0);
  }
  void startPixelSample(IVec2 pixel, uint32_t sampleIndex) {
    stream_.startZSobol(seedHash_, log2Samples_, pixel, sampleIndex);
  }
  float next1D() { return stream_.next1D(); }
  Vec2 next2D() { return stream_.next2D(); }
  Vec2 next2D(uint32_t j, uint32_t n) { return stream_.next2D(j, n); }
  Vec2 next2D(uint32_t j, uint32_t n, uint32_t k, uint32_t m) { return stream_.next2D(j, n, k, m); }
  uint64_t seed() const { return seed_; }
  uint32_t log2Samples() const { return log2Samples_; }

 private:
  uint64_t seed_ = 0, seedHash_ = 0;
  uint32_t log2Samples_ = 0;
  BasicSobolStream<Randomizer> stream_;
};

using SobolSampler = BasicSobolSampler<OwenScrambling>;
using ZSobolSampler = BasicZSobolSampler<OwenScrambling>;

}  // namespace penumbra
