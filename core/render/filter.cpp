#include "core/render/filter.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

namespace {
constexpr int kSubsamples = 16;  // per bin, to integrate |f| accurately
}  // namespace

const char* filterTypeName(FilterType type) {
  switch (type) {
    case FilterType::Box:
      return "box";
    case FilterType::Tent:
      return "tent";
    case FilterType::Gaussian:
      return "gaussian";
    case FilterType::Mitchell:
      return "mitchell";
  }
  return "?";
}

bool parseFilterType(const std::string& name, FilterType& out) {
  for (FilterType t : {FilterType::Box, FilterType::Tent, FilterType::Gaussian, FilterType::Mitchell}) {
    if (name == filterTypeName(t)) {
      out = t;
      return true;
    }
  }
  return false;
}

float defaultFilterRadius(FilterType type) {
  switch (type) {
    case FilterType::Box:
      return 0.5f;
    case FilterType::Tent:
      return 1.f;
    default:
      return 2.f;
  }
}

float evalFilter1D(const FilterDesc& desc, float x) {
  float r = desc.radius;
  x = std::fabs(x);
  if (x > r) return 0.f;
  switch (desc.type) {
    case FilterType::Box:
      return 1.f;
    case FilterType::Tent:
      return std::max(0.f, 1.f - x / r);
    case FilterType::Gaussian: {
      float alpha = -1.f / (2.f * desc.stddev * desc.stddev);
      return std::max(0.f, std::exp(alpha * x * x) - std::exp(alpha * r * r));
    }
    case FilterType::Mitchell: {
      float B = desc.B, C = desc.C;
      x = 2.f * x / r;  // Nori's convention: the cubic's support [0, 2] maps onto [0, radius]
      float x2 = x * x, x3 = x2 * x;
      if (x < 1.f)
        return ((12 - 9 * B - 6 * C) * x3 + (-18 + 12 * B + 6 * C) * x2 + (6 - 2 * B)) * (1.f / 6.f);
      if (x < 2.f)
        return ((-B - 6 * C) * x3 + (6 * B + 30 * C) * x2 + (-12 * B - 48 * C) * x + (8 * B + 24 * C)) *
               (1.f / 6.f);
      return 0.f;
    }
  }
  return 0.f;
}

FilterSampler::FilterSampler(const FilterDesc& desc) : desc_(desc) {
  // Tabulate |f| per bin (integrated with sub-samples) and the signed integral of f.
  std::vector<double> absMass(kBins), signedMass(kBins);
  double absTotal = 0, signedTotal = 0;
  double binWidth = 2.0 * desc.radius / kBins;
  for (int i = 0; i < kBins; ++i) {
    double a = 0, s = 0;
    for (int k = 0; k < kSubsamples; ++k) {
      double x = -desc.radius + (i + (k + 0.5) / kSubsamples) * binWidth;
      double f = evalFilter1D(desc, float(x));
      a += std::fabs(f);
      s += f;
    }
    absMass[i] = a * binWidth / kSubsamples;
    signedMass[i] = s * binWidth / kSubsamples;
    absTotal += absMass[i];
    signedTotal += signedMass[i];
  }
  invBinWidth_ = float(1.0 / binWidth);
  binWeight_.resize(kBins);
  for (int i = 0; i < kBins; ++i) {
    binWeight_[i] = signedMass[i] < 0 ? float(-absTotal / signedTotal) : float(absTotal / signedTotal);
    if (signedMass[i] < 0) signed_ = true;
  }
  // Invert the piecewise-linear CDF at kTable + 1 evenly spaced levels.
  invCdf_.resize(kTable + 1);
  double acc = 0;
  int bin = 0;
  for (int k = 0; k <= kTable; ++k) {
    double level = absTotal * k / kTable;
    while (bin < kBins - 1 && acc + absMass[bin] < level) acc += absMass[bin++];
    double frac = absMass[bin] > 0 ? std::clamp((level - acc) / absMass[bin], 0.0, 1.0) : 0.0;
    invCdf_[k] = float(-desc.radius + (bin + frac) * binWidth);
  }
  invCdf_[0] = -desc.radius;
  invCdf_[kTable] = desc.radius;
}

}  // namespace penumbra
