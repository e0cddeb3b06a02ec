// Pixel reconstruction filters (Nori's rfilter: box, tent, gaussian, mitchell), separable in x and y,
// and their importance sampling: each camera sample's offset from the pixel centre is drawn in
// proportion to |f|, weighted by f / pdf, so nothing is splatted into neighbouring pixels (pbrt-v4).
#pragma once

#include <string>
#include <vector>

#include "core/math/vec.h"

namespace penumbra {

enum class FilterType : uint8_t { Box, Tent, Gaussian, Mitchell };

struct FilterDesc {
  FilterType type = FilterType::Gaussian;
  float radius = 2.f;     // box default 0.5, tent 1, gaussian 2, mitchell 2
  float stddev = 0.5f;    // gaussian
  float B = 1.f / 3.f;    // mitchell
  float C = 1.f / 3.f;    // mitchell
};

const char* filterTypeName(FilterType type);
bool parseFilterType(const std::string& name, FilterType& out);
float defaultFilterRadius(FilterType type);

// The 1-D filter profile f(x), zero outside [-radius, radius].
float evalFilter1D(const FilterDesc& desc, float x);

class FilterSampler {
 public:
  explicit FilterSampler(const FilterDesc& desc = {});

  // Offset from the pixel centre in [-r, r]^2 and the sample's weight f / (pdf * integral of f).
  Vec2 sample(Vec2 u, float& weight) const {
    float wx, wy;
    Vec2 offset(sample1D(u.x, wx), sample1D(u.y, wy));
    weight = wx * wy;
    return offset;
  }

  const FilterDesc& desc() const { return desc_; }

 private:
  float sample1D(float u, float& weight) const;

  FilterDesc desc_;
  bool isBox_ = true;
  std::vector<float> cdf_;        // kBins + 1 entries over [-radius, radius], cdf_[kBins] = 1
  std::vector<float> binWeight_;  // per bin: sign(f) * integral|f| / integral f / bin pdf mass
  // guide_[j]: the bin holding u = j / kGuide. A lookup plus a short forward scan replaces a binary
  // search whose unpredictable branches cost more than the rest of a camera sample.
  std::vector<uint16_t> guide_;
};

}  // namespace penumbra
