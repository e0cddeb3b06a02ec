// Kensler's hashed permutation ("Correlated Multi-Jittered Sampling", Pixar 2013): the stratified
// sampler's order of strata, per pixel and dimension.
#pragma once

#include <cstdint>

namespace penumbra {

// The permutation's working mask for [0, n): n - 1 with every bit below its highest set, so the hash
// permutes [0, mask] and cycle walking keeps the values below n.
inline uint32_t kenslerPermutationMask(uint32_t n) {
  uint32_t w = n - 1;
  w |= w >> 1;
  w |= w >> 2;
  w |= w >> 4;
  w |= w >> 8;
  w |= w >> 16;
  return w;
}

// Element i of the permutation of [0, n) chosen by `key`, without storing the permutation: a hash
// that is a bijection on [0, mask], applied again (cycle walking) until it lands below n.
inline uint32_t kenslerPermute(uint32_t i, uint32_t n, uint32_t key) {
  const uint32_t w = kenslerPermutationMask(n);
  do {
    i ^= key;
    i *= 0xe170893d;
    i ^= key >> 16;
    i ^= (i & w) >> 4;
    i ^= key >> 8;
    i *= 0x0929eb3f;
    i ^= key >> 23;
    i ^= (i & w) >> 1;
    i *= 1 | key >> 27;
    i *= 0x6935fa69;
    i ^= (i & w) >> 11;
    i *= 0x74dcb303;
    i ^= (i & w) >> 2;
    i *= 0x9e501cc3;
    i ^= (i & w) >> 2;
    i *= 0xc860a3df;
    i &= w;
    i ^= i >> 5;
  } while (i >= n);
  return (i + key) % n;
}

}  // namespace penumbra
