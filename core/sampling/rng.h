// Random numbers for the whole renderer: PCG32 (O'Neill 2014, Debian libpcg-cpp-dev) plus the
// hashing used to derive independent streams from (seed, pixel, sample index, dimension).
#pragma once

#include <pcg_random.hpp>

#include <cstdint>

namespace penumbra {

// SplitMix64 finaliser (Steele et al. 2014): a cheap, well-mixed 64-bit hash.
inline constexpr uint64_t mix64(uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  x ^= x >> 31;
  return x;
}

// Combines two values into one well-mixed hash (order matters).
inline constexpr uint64_t hashCombine(uint64_t a, uint64_t b) {
  return mix64(a ^ (b + 0x9e3779b97f4a7c15ULL));
}

// The word pixel (x, y)'s sample streams combine with the seed's hash: x in the high half, y in the low.
inline constexpr uint64_t pixelStreamWord(uint32_t x, uint32_t y) {
  return (static_cast<uint64_t>(x) << 32) | y;
}
// The key of pixel (x, y)'s sample streams.
inline constexpr uint64_t pixelStreamKey(uint64_t seedHash, uint32_t x, uint32_t y) {
  return hashCombine(seedHash, pixelStreamWord(x, y));
}

// Converts 32 random bits to a float in [0, 1): the top 24 bits times 2^-24, so the largest value
// is exactly kOneMinusEpsilon (1 - 2^-24) and 1.0 is never produced.
inline float bitsToUnitFloat(uint32_t bits) {
  return static_cast<float>(bits >> 8) * 0x1p-24f;
}

class Rng {
 public:
  Rng() = default;
  Rng(uint64_t state, uint64_t stream) : pcg_(state, stream) {}

  // Restarts at `state` on the sequence selected by `stream` (2^63 distinct sequences).
  void seed(uint64_t state, uint64_t stream) { pcg_.seed(state, stream); }
  void advance(uint64_t delta) { pcg_.advance(delta); }

  uint32_t nextU32() { return pcg_(); }
  // Uniform in [0, 1), never 1.0.
  float nextFloat() { return bitsToUnitFloat(pcg_()); }
  // Uniform in [0, 1) with 53-bit resolution.
  double nextDouble() {
    uint64_t hi = pcg_() >> 5, lo = pcg_() >> 6;
    return static_cast<double>((hi << 26) | lo) * 0x1p-53;
  }

 private:
  pcg32 pcg_;
};

}  // namespace penumbra
