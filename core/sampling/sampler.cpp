#include "core/sampling/sampler.h"

#include <algorithm>
#include <cmath>

#include "core/sampling/kensler_permutation.h"

namespace penumbra {

namespace {

// (stratum + jitter) / strata, kept below 1 when the float sum rounds up.
inline float jittered(uint32_t stratum, float jitter, float invStrata) {
  return std::min((static_cast<float>(stratum) + jitter) * invStrata, kOneMinusEpsilon);
}

}  // namespace

uint32_t stratifiedGridSide(uint32_t sampleCount) {
  const uint64_t n = std::max<uint32_t>(sampleCount, 1);
  auto side = static_cast<uint64_t>(std::sqrt(static_cast<double>(n)));
  while (side * side > n) --side;
  while ((side + 1) * (side + 1) <= n) ++side;
  return static_cast<uint32_t>(side);
}

Sampler::Sampler(SamplerKind kind, uint32_t sampleCount, uint64_t seed)
    : seed_(seed), seedHash_(mix64(seed)), sampleCount_(std::max<uint32_t>(sampleCount, 1)), kind_(kind) {
  gridSide_ = stratifiedGridSide(sampleCount_);
  zsobolLog2Samples_ = penumbra::zsobolLog2Samples(sampleCount_);
  startPixelSample(IVec2(0, 0), 0);
}

void Sampler::startPixelSample(IVec2 pixel, uint32_t sampleIndex) {
  if (kind_ == SamplerKind::Sobol) return sobol_.startSobol(seedHash_, pixel, sampleIndex);
  if (kind_ == SamplerKind::ZSobol)
    return sobol_.startZSobol(seedHash_, zsobolLog2Samples_, pixel, sampleIndex);
  pixelKey_ = pixelStreamKey(seedHash_, static_cast<uint32_t>(pixel.x), static_cast<uint32_t>(pixel.y));
  sampleIndex_ = sampleIndex;
  dimension_ = 0;
  // The sequence (stream) is chosen by the pixel; the starting state by the sample index.
  rng_.seed(hashCombine(pixelKey_, sampleIndex), pixelKey_);
}

float Sampler::sobol1D() {
  return sobol_.next1D();
}
Vec2 Sampler::sobol2D() {
  return sobol_.next2D();
}
Vec2 Sampler::sobolArray2D(uint32_t j, uint32_t n) {
  return sobol_.next2D(j, n);
}
Vec2 Sampler::sobolInterleaved2D(uint32_t j, uint32_t n, uint32_t k, uint32_t m) {
  return sobol_.next2D(j, n, k, m);
}

uint64_t Sampler::dimensionKey(uint32_t epoch) const {
  return hashCombine(pixelKey_, (static_cast<uint64_t>(epoch) << 32) | dimension_);
}

float Sampler::stratified1D() {
  uint32_t n = sampleCount_;
  uint32_t stratum =
      kenslerPermute(sampleIndex_ % n, n, static_cast<uint32_t>(dimensionKey(sampleIndex_ / n)));
  ++dimension_;
  return jittered(stratum, rng_.nextFloat(), 1.f / static_cast<float>(n));
}

Vec2 Sampler::stratified2D() {
  uint32_t side = gridSide_, n = side * side;
  uint32_t stratum =
      kenslerPermute(sampleIndex_ % n, n, static_cast<uint32_t>(dimensionKey(sampleIndex_ / n)));
  ++dimension_;
  float inv = 1.f / static_cast<float>(side);
  float jx = rng_.nextFloat();
  float jy = rng_.nextFloat();
  return Vec2(jittered(stratum % side, jx, inv), jittered(stratum / side, jy, inv));
}

}  // namespace penumbra
