#include "core/sampling/sobol_matrices.h"

#include <gtest/gtest.h>
#include <boost/random/sobol.hpp>

#include <random>

#include "core/sampling/owen_scramble.h"

namespace penumbra {
namespace {

TEST(SobolMatrices, DimensionZeroIsVanDerCorput) {
  SobolMatrix v = sobolMatrix(0);
  for (uint32_t j = 0; j < 32; ++j) EXPECT_EQ(v[j], 1u << (31 - j));
  for (uint32_t i : {0u, 1u, 2u, 3u, 12345u}) EXPECT_EQ(sobolProduct(v, i), reverseBits32(i));
}

// Every dimension is a (0,1)-sequence: column j's lowest set bit is digit j + 1 (m_j odd, < 2^(j+1)).
TEST(SobolMatrices, EveryColumnHasUnitDiagonal) {
  for (unsigned d : {0u, 1u, 2u, 3u, 4u, 5u, 10u, 31u, 100u, 1000u, kSobolDimensions - 1}) {
    SobolMatrix v = sobolMatrix(d);
    for (uint32_t j = 0; j < 32; ++j) EXPECT_EQ(v[j] & (0u - v[j]), 1u << (31 - j)) << "dimension " << d;
  }
  EXPECT_THROW(sobolMatrix(kSobolDimensions), std::out_of_range);
}

// Dimension 1 (polynomial x + 1) is Pascal's triangle mod 2: digit r of column j is C(j, r) mod 2,
// which by Lucas' theorem is 1 exactly when r's bits are a subset of j's.
TEST(SobolMatrices, DimensionOneIsPascalsTriangleModTwo) {
  SobolMatrix v = sobolMatrix(1);
  for (uint32_t j = 0; j < 32; ++j)
    for (uint32_t r = 0; r < 32; ++r)
      EXPECT_EQ((v[j] >> (31 - r)) & 1, (r & j) == r ? 1u : 0u) << j << "," << r;
}

// The samplers' four-lookup product is both matrix products of the reversed index (all are linear:
// basis vectors suffice; random indices check the byte split).
TEST(SobolMatrices, PairTablesEqualTheMatrixProducts) {
  SobolMatrix v0 = sobolMatrix(0), v1 = sobolMatrix(1);
  auto expected = [&](uint32_t index) {
    return (uint64_t{reverseBits32(sobolProduct(v1, index))} << 32) | reverseBits32(sobolProduct(v0, index));
  };
  for (uint32_t j = 0; j < 32; ++j) EXPECT_EQ(sobolPairDigits(reverseBits32(1u << j)), expected(1u << j));
  std::mt19937 rng(9);
  for (int i = 0; i < 1000; ++i) {
    uint32_t index = rng();
    EXPECT_EQ(sobolPairDigits(reverseBits32(index)), expected(index));
  }
}

// Boost's own generator (Gray-code order, starting at index 1) yields the same points, so the
// recurrence reads the table as Boost does.
TEST(SobolMatrices, AgreesWithBoostSobolEngine) {
  constexpr unsigned kDims = 40;
  boost::random::sobol_engine<uint32_t, 32> engine(kDims);
  std::vector<SobolMatrix> m;
  for (unsigned d = 0; d < kDims; ++d) m.push_back(sobolMatrix(d));
  for (uint32_t k = 1; k <= 2000; ++k) {
    uint32_t gray = k ^ (k >> 1);
    for (unsigned d = 0; d < kDims; ++d)
      ASSERT_EQ(engine(), sobolProduct(m[d], gray)) << "point " << k << " dim " << d;
  }
}

// The pair (0, 1) is a (0,2)-sequence: the first 2^k points put one point in every elementary
// interval of area 2^-k (the samplers rely on this pair only).
TEST(SobolMatrices, DimensionsZeroAndOneFormNets) {
  SobolMatrix v0 = sobolMatrix(0), v1 = sobolMatrix(1);
  for (int k = 0; k <= 12; ++k)
    for (int a = 0; a <= k; ++a) {
      int b = k - a;
      std::vector<int> count(size_t{1} << k, 0);
      for (uint32_t i = 0; i < (1u << k); ++i) {
        uint32_t x = sobolProduct(v0, i), y = sobolProduct(v1, i);
        uint32_t cx = a == 0 ? 0 : x >> (32 - a), cy = b == 0 ? 0 : y >> (32 - b);
        ++count[(cx << b) | cy];
      }
      for (int c : count) ASSERT_EQ(c, 1) << "k=" << k << " a=" << a;
    }
}

}  // namespace
}  // namespace penumbra
