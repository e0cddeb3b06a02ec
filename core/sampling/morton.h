// Morton (Z-order) codes of pixel coordinates: the bits of x and y interleaved, so every aligned
// 2^j x 2^j tile of pixels is one aligned block of 4^j consecutive codes.
#pragma once

#include <cstdint>

namespace penumbra {

// The 32 bits of v moved to the even bit positions of a 64-bit word.
inline uint64_t spreadBitsToEven(uint32_t v) {
  uint64_t x = v;
  x = (x | (x << 16)) & 0x0000ffff0000ffffull;
  x = (x | (x << 8)) & 0x00ff00ff00ff00ffull;
  x = (x | (x << 4)) & 0x0f0f0f0f0f0f0f0full;
  x = (x | (x << 2)) & 0x3333333333333333ull;
  x = (x | (x << 1)) & 0x5555555555555555ull;
  return x;
}

// x in the even bits, y in the odd bits.
inline uint64_t encodeMorton2(uint32_t x, uint32_t y) {
  return spreadBitsToEven(x) | (spreadBitsToEven(y) << 1);
}

}  // namespace penumbra
