// Discrete distribution over n items proportional to non-negative weights, sampled in O(1) with one
// uniform number: Walker's alias method built by Vose's linear-time algorithm (M. D. Vose, "A Linear
// Algorithm for Generating Random Numbers with a Given Distribution", IEEE TSE 17(9), 1991).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace penumbra {

struct AliasTable {
  struct Bin {
    double keep = 1.0;   // probability of keeping this bin's own item
    uint32_t alias = 0;  // the item taken otherwise
    double pmf = 0.0;    // this bin's item's probability, weight / total
  };
  std::vector<Bin> bins;

  uint32_t size() const { return static_cast<uint32_t>(bins.size()); }
  // Item for u in [0, 1) (resolution matters: pass 53-bit u for large tables). Requires size() > 0.
  uint32_t sample(double u) const {
    const double x = u * double(bins.size());
    uint32_t i = static_cast<uint32_t>(x);
    if (i >= bins.size()) i = size() - 1;  // u rounding up to 1
    return x - double(i) < bins[i].keep ? i : bins[i].alias;
  }
  double pmf(uint32_t item) const { return bins[item].pmf; }
};

// Weights that are negative, NaN or infinite count as 0. When every weight is 0 (or there are none
// that count) the distribution is uniform, so the pmfs always sum to 1 for n > 0.
AliasTable makeAliasTable(std::span<const double> weights);

}  // namespace penumbra
