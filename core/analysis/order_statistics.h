// Order statistics of small samples of measurements (benchmark runs, frame times): the median and a
// nearest-rank percentile. An empty sample gives 0.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace penumbra {

// The middle value; for an even count, the mean of the two middle values.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  if (v.size() % 2) return v[mid];
  const double upper = v[mid];
  return 0.5 * (*std::max_element(v.begin(), v.begin() + mid) + upper);
}

// The value at rank floor(n·p) of the sorted sample (0-based, clamped to the last), p in [0, 1]:
// p = 0.9 of 10 values is the largest, of 100 values the 91st.
inline double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  const size_t rank = std::min(v.size() - 1, static_cast<size_t>(double(v.size()) * std::clamp(p, 0.0, 1.0)));
  std::nth_element(v.begin(), v.begin() + rank, v.end());
  return v[rank];
}

}  // namespace penumbra
