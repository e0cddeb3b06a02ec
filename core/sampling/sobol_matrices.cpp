#include "core/sampling/sobol_matrices.h"

#include <boost/random/detail/sobol_table.hpp>

#include <bit>
#include <stdexcept>
#include <string>

#include "core/sampling/owen_scramble.h"

namespace penumbra {

namespace {

using JoeKuoTable = boost::random::detail::qrng_tables::sobol;
static_assert(JoeKuoTable::max_dimension == kSobolDimensions);

SobolPairTables buildPairTables() {
  const SobolMatrix v0 = sobolMatrix(0), v1 = sobolMatrix(1);
  SobolPairTables t{};
  for (int b = 0; b < 4; ++b)
    for (uint32_t byte = 0; byte < 256; ++byte) {
      uint64_t digits = 0;
      for (int k = 0; k < 8; ++k) {
        if ((byte >> k & 1) == 0) continue;
        const int j = 31 - (8 * b + k);  // bit 8b + k of the reversed index is index bit j
        digits ^= (static_cast<uint64_t>(reverseBits32(v1[j])) << 32) | reverseBits32(v0[j]);
      }
      t.byte[b][byte] = digits;
    }
  return t;
}

}  // namespace

// Bratley and Fox (1988), section 2: for the primitive polynomial x^s + a_1 x^(s-1) + ... + 1 and
// the initial m_1..m_s of the table, v_j = a_1 v_(j-1) ^ ... ^ a_(s-1) v_(j-s+1) ^ v_(j-s) ^
// (v_(j-s) >> s) on fractions v_j = m_j / 2^(j+1).
SobolMatrix sobolMatrix(unsigned dimension) {
  if (dimension >= kSobolDimensions)
    throw std::out_of_range("sobolMatrix: dimension " + std::to_string(dimension) +
                            " >= " + std::to_string(kSobolDimensions));
  SobolMatrix v{};
  if (dimension == 0) {
    for (unsigned j = 0; j < 32; ++j) v[j] = 1u << (31 - j);
    return v;
  }
  // Boost stores the whole polynomial (leading and constant terms included) and m_1..m_s.
  const unsigned poly = JoeKuoTable::polynomial(dimension - 1);
  const unsigned degree = static_cast<unsigned>(std::bit_width(poly)) - 1;
  for (unsigned j = 0; j < degree && j < 32; ++j)
    v[j] = static_cast<uint32_t>(JoeKuoTable::minit(dimension - 1, j)) << (31 - j);
  for (unsigned j = degree; j < 32; ++j) {
    uint32_t x = v[j - degree] ^ (v[j - degree] >> degree);
    for (unsigned k = 1; k < degree; ++k)
      if (poly >> (degree - k) & 1) x ^= v[j - k];
    v[j] = x;
  }
  return v;
}

uint32_t sobolProduct(const SobolMatrix& columns, uint32_t index) {
  uint32_t x = 0;
  for (unsigned j = 0; j < 32; ++j) x ^= columns[j] & (0u - (index >> j & 1u));
  return x;
}

const SobolPairTables kSobolPairTables = buildPairTables();

}  // namespace penumbra
