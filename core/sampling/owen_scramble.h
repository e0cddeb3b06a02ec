// Hash-based Owen scrambling (Burley 2020, "Practical Hash-based Owen Scrambling", JCGT 9(4)):
// a random permutation of base-2 digit sequences that maps every elementary interval of [0, 1) onto
// an elementary interval of the same size, so it keeps nets nets, chosen by a 32-bit seed and
// evaluated for one value without storing the permutation tree.
//
// "Digit order": bit 0 holds the most significant binary digit (the reverse of a 32-bit fixed-point
// fraction). Owen scrambling flips each digit depending on the digits before it, i.e. bit j depends
// on bits < j, which is what carries of additions and multiplications by even numbers do.
#pragma once

#include <cstdint>

namespace penumbra {

inline uint32_t reverseBits32(uint32_t x) {
  x = __builtin_bswap32(x);
  x = ((x & 0x0f0f0f0fu) << 4) | ((x >> 4) & 0x0f0f0f0fu);
  x = ((x & 0x33333333u) << 2) | ((x >> 2) & 0x33333333u);
  x = ((x & 0x55555555u) << 1) | ((x >> 1) & 0x55555555u);
  return x;
}

// Burley's Laine-Karras-style permutation (JCGT 9(4), section 3) of a digit-order value: the seed
// addition and each x ^= x * even carry information only towards higher bits, so output bit j is a
// function of input bits <= j (a valid Owen scramble for every seed).
inline uint32_t laineKarrasPermutation(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// Burley's nested uniform scramble of a 32-bit fixed-point fraction (or of an index read most
// significant bit first): reverse, permute, reverse. Applied to a sequence index it is a
// permutation that maps every aligned block of 2^k indices onto an aligned block of 2^k indices.
inline uint32_t nestedUniformScramble(uint32_t x, uint32_t seed) {
  return reverseBits32(laineKarrasPermutation(reverseBits32(x), seed));
}

}  // namespace penumbra
