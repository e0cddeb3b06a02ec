// Pixel reconstruction filters (Nori's rfilter: box, tent, gaussian, mitchell), separable in x and y,
// and their importance sampling: each camera sample's offset from the pixel centre is drawn in
// proportion to |f|, weighted by f / pdf, so nothing is splatted into neighbouring pixels (pbrt-v4).
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "core/math/vec.h"

namespace penumbra {

enum class FilterType : uint8_t { Box, Tent, Gaussian, Mitchell };

struct FilterDesc {
  FilterType type = FilterType::Gaussian;
  float radius = 2.f;   // box default 0.5, tent 1, gaussian 2, mitchell 2
  float stddev = 0.5f;  // gaussian
  float B = 1.f / 3.f;  // mitchell
  float C = 1.f / 3.f;  // mitchell

  bool operator==(const FilterDesc&) const = default;
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
  // Inlined into the row loop: it runs once per camera sample, and GCC stops inlining it there.
  [[gnu::always_inline]] Vec2 sample(Vec2 u, float& weight) const {
    float wx, wy;
    Vec2 offset(sample1D(u.x, wx), sample1D(u.y, wy));
    weight = wx * wy;
    return offset;
  }

  const FilterDesc& desc() const { return desc_; }

  static constexpr int kBins = 512;    // signed-weight bins over [-radius, radius]
  static constexpr int kTable = 1024;  // inverse-CDF entries, uniform in u

  // The tables sample1D reads, for code that samples the filter in SIMD lanes; valid while this lives.
  struct Tables {
    const float* invCdf;     // kTable + 1 entries
    const float* binWeight;  // kBins entries, read when isSigned
    bool isSigned;
    float radius, invBinWidth;
  };
  Tables tables() const { return {invCdf_.data(), binWeight_.data(), signed_, desc_.radius, invBinWidth_}; }

 private:
  // Inverse-CDF lookup with linear interpolation: the sampled density is |f| approximated by
  // kTable pieces (no search, no branches). Positive filters have weight 1; signed ones (Mitchell)
  // take sign(f) * integral|f| / integral f from the bin of x.
  float sample1D(float u, float& weight) const {
    float t = u * float(kTable);
    int k = std::min(int(t), kTable - 1);
    float x = invCdf_[k] + (t - float(k)) * (invCdf_[k + 1] - invCdf_[k]);
    weight = 1.f;
    if (signed_) {
      int bin = std::clamp(int((x + desc_.radius) * invBinWidth_), 0, kBins - 1);
      weight = binWeight_[bin];
    }
    return x;
  }

  FilterDesc desc_;
  bool signed_ = false;  // the filter has negative lobes
  float invBinWidth_ = 1.f;
  std::vector<float> invCdf_;     // kTable + 1 entries: x with CDF(x) = k / kTable
  std::vector<float> binWeight_;  // per bin: sign(f) * integral|f| / integral f
};

}  // namespace penumbra
