// The per-request core of the Sobol' samplers: one point of Sobol' dimensions (0, 1) at a shuffled
// index, Owen-scrambled, as in Burley 2020 ("Practical Hash-based Owen Scrambling", JCGT 9(4),
// section 4) and pbrt-v4's padded Sobol' sampler. Every request (one next1D or next2D) takes its
// own index shuffle and value scrambles from hash(key, request), so consecutive requests are
// independent (0,2)-sequences: "padding". Dimensions 0 and 1 are the first two of Joe and Kuo's
// table, whose pair is a (0,2)-sequence; no request ever needs a higher dimension.
#pragma once

#include <cstdint>

#include "core/math/vec.h"
#include "core/sampling/owen_scramble.h"
#include "core/sampling/rng.h"
#include "core/sampling/sobol_matrices.h"

namespace penumbra {

// The samplers' randomisation: the index shuffled by a nested uniform scramble (a permutation that
// maps aligned blocks of 2^k indices onto aligned blocks, so every power-of-two prefix of a pixel's
// samples stays a net) and every value Owen-scrambled. Tests substitute broken versions.
struct OwenScrambling {
  // reversedIndex: the index with its bits reversed (computed once per pixel sample).
  static uint32_t shuffledIndex(uint32_t reversedIndex, uint32_t seed) {
    return reverseBits32(laineKarrasPermutation(reversedIndex, seed));
  }
  // digits: a point in digit order (bit 0 = most significant digit); returns digit order.
  static uint32_t scrambledDigits(uint32_t digits, uint32_t seed) {
    return laineKarrasPermutation(digits, seed);
  }
};

// One request's point. reversedIndex: the bit-reversed sequence index before shuffling;
// indexXor: bits XORed into the shuffled index (the zsobol sampler's sample counts beyond its
// tile net); key: the stream's hash (seed, pixel or pixel tile).
template <class Randomizer>
inline float sobolPoint1D(uint32_t reversedIndex, uint32_t indexXor, uint64_t key, uint32_t request) {
  const uint64_t h = hashCombine(key, request);
  const uint32_t index = Randomizer::shuffledIndex(reversedIndex, static_cast<uint32_t>(h)) ^ indexXor;
  // Dimension 0 in digit order is the index itself (van der Corput).
  const uint32_t x = Randomizer::scrambledDigits(index, static_cast<uint32_t>(h >> 32));
  return bitsToUnitFloat(reverseBits32(x));
}

template <class Randomizer>
inline Vec2 sobolPoint2D(uint32_t reversedIndex, uint32_t indexXor, uint64_t key, uint32_t request) {
  const uint64_t h = hashCombine(key, request);
  const uint32_t index = Randomizer::shuffledIndex(reversedIndex, static_cast<uint32_t>(h)) ^ indexXor;
  const uint32_t x = Randomizer::scrambledDigits(index, static_cast<uint32_t>(h >> 32));
  const uint32_t y =
      Randomizer::scrambledDigits(sobolDimension1Digits(index), static_cast<uint32_t>(mix64(h)));
  // One 64-bit reversal turns both digit-order values into fractions: x lands in the high word.
  const uint64_t fractions = reverseBits64((static_cast<uint64_t>(y) << 32) | x);
  return Vec2(bitsToUnitFloat(static_cast<uint32_t>(fractions >> 32)),
              bitsToUnitFloat(static_cast<uint32_t>(fractions)));
}

}  // namespace penumbra
