#include "core/lights/alias_table.h"

#include <cmath>

namespace penumbra {

// Vose's algorithm: items below the mean fill their bin's remainder from items above it.
AliasTable makeAliasTable(std::span<const double> weights) {
  AliasTable table;
  const size_t n = weights.size();
  table.bins.resize(n);
  if (n == 0) return table;
  auto usable = [](double w) { return std::isfinite(w) && w > 0.0 ? w : 0.0; };
  double total = 0.0;
  for (double w : weights) total += usable(w);
  const bool uniform = !(total > 0.0) || !std::isfinite(total);
  std::vector<double> scaled(n);
  for (size_t i = 0; i < n; ++i) {
    table.bins[i].pmf = uniform ? 1.0 / double(n) : usable(weights[i]) / total;
    scaled[i] = table.bins[i].pmf * double(n);
  }
  std::vector<uint32_t> small, large;
  for (uint32_t i = 0; i < n; ++i) (scaled[i] < 1.0 ? small : large).push_back(i);
  while (!small.empty() && !large.empty()) {
    const uint32_t s = small.back(), l = large.back();
    small.pop_back();
    large.pop_back();
    table.bins[s].keep = scaled[s];
    table.bins[s].alias = l;
    scaled[l] = (scaled[l] + scaled[s]) - 1.0;
    (scaled[l] < 1.0 ? small : large).push_back(l);
  }
  // What is left is 1 up to rounding; a left-over zero-weight item must still never be drawn.
  for (uint32_t i : large) table.bins[i] = {1.0, i, table.bins[i].pmf};
  uint32_t heaviest = 0;
  for (uint32_t i = 1; i < n; ++i)
    if (table.bins[i].pmf > table.bins[heaviest].pmf) heaviest = i;
  for (uint32_t i : small)
    table.bins[i] = table.bins[i].pmf > 0.0 ? AliasTable::Bin{1.0, i, table.bins[i].pmf}
                                            : AliasTable::Bin{0.0, heaviest, 0.0};
  return table;
}

}  // namespace penumbra
