// Generator matrices of the Sobol' sequence with Joe and Kuo's direction numbers ("Constructing Sobol
// sequences with better two-dimensional projections", SIAM J. Sci. Comput. 30, 2008), read from the
// copy Boost.Random ships (Debian libboost-dev: boost/random/detail/sobol_table.hpp).
//
// A matrix is stored by columns: column j is the 32-bit fixed-point fraction v_j that index bit j
// contributes, so the point of index i in one dimension is the XOR of v_j over the set bits of i.
#pragma once

#include <array>
#include <cstdint>

namespace penumbra {

using SobolMatrix = std::array<uint32_t, 32>;

// Dimensions Boost's table covers (dimension 0 is van der Corput's, the others one primitive
// polynomial each).
inline constexpr unsigned kSobolDimensions = 3667;

// The generator matrix of one dimension (< kSobolDimensions), built from the table by Bratley and
// Fox's recurrence (ACM TOMS 14, 1988). Not for per-sample use: builds 32 columns.
SobolMatrix sobolMatrix(unsigned dimension);

// Matrix-vector product over GF(2): the unscrambled 32-bit fraction of index i (branch-free).
uint32_t sobolProduct(const SobolMatrix& columns, uint32_t index);

// Dimensions 0 and 1 in digit order (bit 0 = most significant digit) of the index whose bits are
// reversed: the samplers' shuffle produces the index bit-reversed, and both dimensions are linear
// maps of it over GF(2), so four tables of 256 XOR combinations (one per byte, built once at
// start-up from sobolMatrix(0) and sobolMatrix(1)) give both without any bit reversal.
// Low word: dimension 0 (the index itself, van der Corput); high word: dimension 1.
struct SobolPairTables {
  uint64_t byte[4][256];
};
extern const SobolPairTables kSobolPairTables;

inline uint64_t sobolPairDigits(uint32_t reversedIndex) {
  const auto& t = kSobolPairTables.byte;
  return t[0][reversedIndex & 0xff] ^ t[1][(reversedIndex >> 8) & 0xff] ^ t[2][(reversedIndex >> 16) & 0xff] ^
         t[3][reversedIndex >> 24];
}

}  // namespace penumbra
