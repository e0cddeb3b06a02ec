// The per-request core of the Sobol' samplers: one point of Sobol' dimensions (0, 1) at a shuffled
// index, Owen-scrambled, as in Burley 2020 ("Practical Hash-based Owen Scrambling", JCGT 9(4),
// section 4) and pbrt-v4's padded Sobol' sampler. Every request (one next1D or next2D) takes its
// own index shuffle and value scrambles from hash(key, request), so consecutive requests are
// independent (0,2)-sequences: "padding". Dimensions 0 and 1 are the first two of Joe and Kuo's
// table, whose pair is a (0,2)-sequence; no request ever needs a higher dimension.
//
// Why the shuffle keeps nets: a Sobol' point's first a digits depend on every index bit, but the
// block [c 2^k, (c + 1) 2^k) fixes all bits from k up, so each aligned block of 2^k indices is the
// net of indices [0, 2^k) up to a digital shift. The shuffle maps aligned blocks onto aligned blocks.
#pragma once

#include <cstdint>

#include "core/math/vec.h"
#include "core/sampling/digits_to_float.h"
#include "core/sampling/owen_scramble.h"
#include "core/sampling/rng.h"
#include "core/sampling/sobol_matrices.h"

namespace penumbra {

// The samplers' randomisation. Tests substitute broken versions.
struct OwenScrambling {
  // Burley's nested uniform scramble of an index (most significant bit first), taken and returned
  // bit-reversed: maps every aligned block of 2^k indices onto an aligned block (for zsobol: whole
  // pixel tiles).
  static uint32_t shuffledReversedIndex(uint32_t reversedIndex, uint32_t seed) {
    return laineKarrasPermutation(reversedIndex, seed);
  }
  // digits: a point in digit order (bit 0 = most significant digit); returns digit order.
  static uint32_t scrambledDigits(uint32_t digits, uint32_t seed) {
    return laineKarrasPermutation(digits, seed);
  }
};

// The request's hash: its low word seeds the index shuffle, the rest the value scrambles.
inline uint64_t requestHash(uint64_t key, uint32_t request) {
  return hashCombine(key, request);
}

// The points of a shuffled index, given bit-reversed. Dimension 0 in digit order is the index.
template <class Randomizer>
inline float sobolPoint1D(uint32_t shuffledReversedIndex, uint64_t hash) {
  const uint32_t x =
      Randomizer::scrambledDigits(reverseBits32(shuffledReversedIndex), static_cast<uint32_t>(hash >> 32));
  return digitsToUnitFloat(x);
}

template <class Randomizer>
inline Vec2 sobolPoint2D(uint32_t shuffledReversedIndex, uint64_t hash) {
  const uint64_t digits = sobolPairDigits(shuffledReversedIndex);
  const uint32_t x =
      Randomizer::scrambledDigits(static_cast<uint32_t>(digits), static_cast<uint32_t>(hash >> 32));
  // A third 32-bit seed from the high half of an odd multiple (depends on every bit of the hash).
  const auto ySeed = static_cast<uint32_t>((hash * 0x9e3779b97f4a7c15ull) >> 32);
  const uint32_t y = Randomizer::scrambledDigits(static_cast<uint32_t>(digits >> 32), ySeed);
  return Vec2(digitsToUnitFloat(x), digitsToUnitFloat(y));
}

}  // namespace penumbra
