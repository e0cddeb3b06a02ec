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

// Dimension 1 in digit order (bit 0 = most significant digit), for the samplers: four tables of 256
// XOR combinations of 8 consecutive columns each, built once at start-up from sobolMatrix(1), so the
// product is four lookups. Dimension 0 needs none: in digit order its point is the index itself.
struct SobolDimension1Tables {
  uint32_t byte[4][256];
};
extern const SobolDimension1Tables kSobolDimension1;

inline uint32_t sobolDimension1Digits(uint32_t index) {
  const auto& t = kSobolDimension1.byte;
  return t[0][index & 0xff] ^ t[1][(index >> 8) & 0xff] ^ t[2][(index >> 16) & 0xff] ^ t[3][index >> 24];
}

}  // namespace penumbra
