#include "core/sampling/owen_scramble.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

namespace penumbra {
namespace {

uint64_t reverseSlowly(uint64_t x, int bits) {
  uint64_t r = 0;
  for (int i = 0; i < bits; ++i) r |= ((x >> i) & 1) << (bits - 1 - i);
  return r;
}

TEST(OwenScramble, ReverseBitsMatchesBitByBitReversal) {
  std::mt19937_64 rng(3);
  for (int i = 0; i < 1000; ++i) {
    uint64_t x = rng();
    EXPECT_EQ(reverseBits32(static_cast<uint32_t>(x)), reverseSlowly(static_cast<uint32_t>(x), 32));
  }
}

// Owen scrambling in digit order: flipping input bit j never changes output bits below j.
TEST(OwenScramble, LaineKarrasOutputBitDependsOnlyOnLowerInputBits) {
  std::mt19937 rng(5);
  for (int i = 0; i < 2000; ++i) {
    uint32_t x = rng(), seed = rng();
    int j = static_cast<int>(rng() % 32);
    uint32_t a = laineKarrasPermutation(x, seed), b = laineKarrasPermutation(x ^ (1u << j), seed);
    uint32_t below = j == 0 ? 0u : (~0u >> (32 - j));
    EXPECT_EQ(a & below, b & below) << "bit " << j;
    EXPECT_NE(a, b);  // and the permutation is a bijection on the bits from j on
  }
}

// The nested scramble of an index maps each aligned block of 2^k indices onto one aligned block.
TEST(OwenScramble, NestedScrambleMapsAlignedBlocksOntoAlignedBlocks) {
  for (uint32_t seed : {0u, 1u, 0x9e3779b9u, 0xdeadbeefu}) {
    for (int k : {0, 1, 5, 10}) {
      for (uint32_t block : {0u, 1u, 77u, 4000u}) {
        std::set<uint32_t> low;
        uint32_t high = nestedUniformScramble(block << k, seed) >> k;
        for (uint32_t t = 0; t < (1u << k); ++t) {
          uint32_t s = nestedUniformScramble((block << k) | t, seed);
          EXPECT_EQ(s >> k, high);
          low.insert(s & ((1u << k) - 1));
        }
        EXPECT_EQ(low.size(), 1u << k);
      }
    }
  }
}

TEST(OwenScramble, SeedsChooseDifferentPermutations) {
  std::set<uint32_t> images;
  for (uint32_t seed = 0; seed < 64; ++seed)
    images.insert(nestedUniformScramble(0x12345678u, seed * 0x9e3779b9u));
  EXPECT_GT(images.size(), 60u);
}

}  // namespace
}  // namespace penumbra
