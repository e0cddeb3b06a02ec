// The yardsticks' random numbers: an xorshift-multiply generator, the cheapest stream that is good
// enough for a hand-written loop measured against the renderer.
#pragma once

#include <cstdint>

namespace penumbra {

struct FastRng {
  uint64_t s;
  float next() {
    s ^= s >> 12, s ^= s << 25, s ^= s >> 27;
    return float((s * 0x2545F4914F6CDD1DULL) >> 40) * 0x1p-24f;
  }
};

}  // namespace penumbra
