#include "core/render/filter.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

// The importance-sampled filter must reproduce integrals against the (normalised) filter:
// E[w g(X)] = integral f g / integral f, for a smooth test function g.
double filterExpectation(const FilterDesc& d, double (*g)(double)) {
  FilterSampler fs(d);
  const int n = 200000;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    float u = (i + 0.5f) / n;
    float w;
    Vec2 off = fs.sample(Vec2(u, 0.5f), w);
    float wy;
    fs.sample(Vec2(0.5f, 0.5f), wy);
    sum += (w / std::sqrt(wy)) * g(off.x);  // wy = (weight at the centre)^2 of both axes
  }
  return sum / n;
}

double quadrature(const FilterDesc& d, double (*g)(double)) {
  double num = 0, den = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    double x = -d.radius + (i + 0.5) * 2.0 * d.radius / n;
    double f = evalFilter1D(d, float(x));
    num += f * g(x);
    den += f;
  }
  return num / den;
}

double square(double x) {
  return x * x;
}
double bump(double x) {
  return std::cos(x) + 0.3 * x;
}

TEST(FilterSampler, ReproducesTheFilterForEveryType) {
  for (FilterType t : {FilterType::Box, FilterType::Tent, FilterType::Gaussian, FilterType::Mitchell}) {
    FilterDesc d;
    d.type = t;
    d.radius = defaultFilterRadius(t);
    for (auto g : {square, bump})
      EXPECT_NEAR(filterExpectation(d, g), quadrature(d, g), 2e-3) << filterTypeName(t);
  }
}

TEST(FilterSampler, OffsetsStayInsideTheRadiusAndWeightsAreFinite) {
  for (FilterType t : {FilterType::Box, FilterType::Tent, FilterType::Gaussian, FilterType::Mitchell}) {
    FilterDesc d;
    d.type = t;
    d.radius = defaultFilterRadius(t);
    FilterSampler fs(d);
    for (float u : {0.f, 1e-7f, 0.5f, 0.9999f, kOneMinusEpsilon}) {
      float w;
      Vec2 off = fs.sample(Vec2(u, u), w);
      EXPECT_LE(std::fabs(off.x), d.radius);
      EXPECT_TRUE(std::isfinite(w));
    }
  }
}

TEST(FilterSampler, PositiveFiltersHaveUnitWeights) {
  FilterSampler fs(FilterDesc{});  // gaussian
  for (int i = 0; i < 100; ++i) {
    float w;
    fs.sample(Vec2((i + 0.5f) / 100.f, 0.3f), w);
    EXPECT_NEAR(w, 1.f, 1e-5f);
  }
}

}  // namespace
}  // namespace penumbra
