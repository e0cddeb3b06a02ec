// A value in digit order (bit 0 = the most significant binary digit, as Owen scrambling produces
// it) to a float in [0, 1) without reversing its bits: equal to bitsToUnitFloat(reverseBits32(x)).
// The top 24 digits are bytes 0..2 of x; each byte's digits, reversed and scaled, come from a table
// of 256 floats, and the three exact terms (multiples of 2^-24 below 1) add up exactly.
#pragma once

#include <array>
#include <cstdint>

namespace penumbra {

struct DigitByteFloats {
  float byte[3][256];  // byte[k][b]: the fraction whose digits 8k + 1 .. 8k + 8 are b's bits 0..7
};

inline constexpr DigitByteFloats kDigitByteFloats = [] {
  DigitByteFloats t{};
  for (int k = 0; k < 3; ++k)
    for (uint32_t b = 0; b < 256; ++b) {
      float v = 0.f, digit = 0.5f;
      for (int k2 = 0; k2 < 8 * k; ++k2) digit *= 0.5f;
      for (int i = 0; i < 8; ++i, digit *= 0.5f)
        if (b >> i & 1) v += digit;
      t.byte[k][b] = v;
    }
  return t;
}();

inline float digitsToUnitFloat(uint32_t digits) {
  const auto& t = kDigitByteFloats.byte;
  return t[0][digits & 0xff] + t[1][(digits >> 8) & 0xff] + t[2][(digits >> 16) & 0xff];
}

}  // namespace penumbra
