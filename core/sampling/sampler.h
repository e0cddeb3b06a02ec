// Per-pixel sample streams for the integrators. A stream is a pure function of
// (seed, pixel, sample index): images do not depend on thread count or scheduling.
// Concrete (no virtual calls): the engine owns one Sampler per worker and restarts it per pixel sample.
#pragma once

#include <cstdint>
#include <string>

#include "core/math/vec.h"
#include "core/sampling/rng.h"
#include "core/sampling/sobol_stream.h"

namespace penumbra {

// One row per kind in core/sampling/sampler_table.h (names, labels, which settings apply).
// Sobol and ZSobol: core/sampling/sobol_stream.h.
enum class SamplerKind : uint8_t { Independent, Stratified, Sobol, ZSobol };
inline constexpr int kSamplerKindCount = 4;

// Stratified's strata per side of its 2-D grid for a sampleCount: floor(sqrt(max(sampleCount, 1))).
uint32_t stratifiedGridSide(uint32_t sampleCount);

class Sampler {
 public:
  // sampleCount: the scene's samples per pixel; for Stratified it is the number of strata per
  // dimension pair (rounded down to a square), repeating with fresh jitter beyond it; for ZSobol the
  // count (rounded up to a power of two) at which neighbouring pixels share one net.
  Sampler(SamplerKind kind, uint32_t sampleCount, uint64_t seed);

  // Restarts the stream for one pixel sample. Cheap: called once per camera sample.
  void startPixelSample(IVec2 pixel, uint32_t sampleIndex);

  // Uniform in [0, 1): never returns 1.0.
  float next1D();
  Vec2 next2D();
  // Point j of n (j = 0 .. n - 1, in order) of one 2-D request, for n samples of one pixel sample
  // (e.g. its shadow rays): the Sobol' samplers stratify them among themselves and across pixel
  // samples (core/sampling/sobol_stream.h); the others give n plain next2D values.
  Vec2 next2D(uint32_t j, uint32_t n);
  // Point j of n of the k-th of m such requests drawn interleaved (each shading sample draws its m
  // values before the next sample draws its): each of the m is stratified like next2D(j, n).
  Vec2 next2D(uint32_t j, uint32_t n, uint32_t k, uint32_t m);

  SamplerKind kind() const;
  uint32_t sampleCount() const;
  uint64_t seed() const;
  // mix64(seed()): what every stream's key starts from (pixelStreamKey, zsobolTileKey).
  uint64_t seedHash() const;
  // Stratified: strata per side of the 2-D grid (stratifiedGridSide(sampleCount())).
  uint32_t gridSide() const;
  // ZSobol: zsobolLog2Samples(sampleCount()).
  uint32_t zsobolLog2Samples() const;

 private:
  // The Sobol' kinds' draws are out-of-line calls, so next1D/next2D stay small enough to be inlined
  // into the integrators and the row loop for every kind.
  float sobol1D();
  Vec2 sobol2D();
  Vec2 sobolArray2D(uint32_t j, uint32_t n);
  Vec2 sobolInterleaved2D(uint32_t j, uint32_t n, uint32_t k, uint32_t m);
  float stratified1D();
  Vec2 stratified2D();
  // Key of the (pixel, dimension, epoch) permutation of strata; epoch = sampleIndex / strata.
  uint64_t dimensionKey(uint32_t epoch) const;

  Rng rng_;
  SobolStream sobol_;
  uint32_t zsobolLog2Samples_ = 0;
  uint64_t seed_ = 0;
  uint64_t seedHash_ = 0;     // mix64(seed_), hoisted out of startPixelSample
  uint64_t pixelKey_ = 0;     // hash of (seed, pixel)
  uint32_t sampleCount_ = 1;  // N: strata of 1-D dimensions
  uint32_t gridSide_ = 1;     // floor(sqrt(N)): 2-D dimensions use gridSide^2 strata
  uint32_t sampleIndex_ = 0;
  uint32_t dimension_ = 0;  // dimensions consumed since startPixelSample
  SamplerKind kind_ = SamplerKind::Independent;
};

inline float Sampler::next1D() {
  if (kind_ == SamplerKind::Stratified) return stratified1D();
  if (kind_ >= SamplerKind::Sobol) return sobol1D();
  ++dimension_;
  return rng_.nextFloat();
}

inline Vec2 Sampler::next2D() {
  if (kind_ == SamplerKind::Stratified) return stratified2D();
  if (kind_ >= SamplerKind::Sobol) return sobol2D();
  ++dimension_;
  float x = rng_.nextFloat();
  return Vec2(x, rng_.nextFloat());
}

inline Vec2 Sampler::next2D(uint32_t j, uint32_t n) {
  if (kind_ >= SamplerKind::Sobol) return n == 1 ? sobol2D() : sobolArray2D(j, n);
  return next2D();
}

inline Vec2 Sampler::next2D(uint32_t j, uint32_t n, uint32_t k, uint32_t m) {
  if (kind_ >= SamplerKind::Sobol) return sobolInterleaved2D(j, n, k, m);
  return next2D();
}

inline SamplerKind Sampler::kind() const {
  return kind_;
}
inline uint32_t Sampler::sampleCount() const {
  return sampleCount_;
}
inline uint64_t Sampler::seed() const {
  return seed_;
}
inline uint64_t Sampler::seedHash() const {
  return seedHash_;
}
inline uint32_t Sampler::gridSide() const {
  return gridSide_;
}
inline uint32_t Sampler::zsobolLog2Samples() const {
  return zsobolLog2Samples_;
}

}  // namespace penumbra
