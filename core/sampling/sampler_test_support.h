// Measurements of sample streams for the samplers' tests (not used by the renderer): exact net
// property, neighbour correlation, the spread of a smooth integrand's estimates and its convergence
// rate. Each returns what it measured, so a test can require a pass of a sampler and a failure of a
// deliberately broken one. S is any sampler with startPixelSample(IVec2, uint32_t), next1D, next2D.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/math/vec.h"

namespace penumbra {

// Where a point set fails to be a (0, k, 2)-net of 2^k points (empty when it is one): every
// elementary interval 2^-a x 2^-b, a + b = k, must hold exactly one point.
inline std::string netDefect(const std::vector<Vec2>& points, int k) {
  if (points.size() != (size_t{1} << k)) return "expected 2^" + std::to_string(k) + " points";
  for (int a = 0; a <= k; ++a) {
    const int b = k - a;
    std::vector<uint8_t> count(points.size(), 0);
    for (const Vec2& p : points) {
      // Scaling by a power of two is exact, so the cell is exactly floor(x 2^a), floor(y 2^b).
      const auto cx = static_cast<uint32_t>(std::ldexp(p.x, a)),
                 cy = static_cast<uint32_t>(std::ldexp(p.y, b));
      const size_t cell = (static_cast<size_t>(cx) << b) | cy;
      if (cell >= count.size() || ++count[cell] > 1)
        return "two points in a 2^-" + std::to_string(a) + " x 2^-" + std::to_string(b) + " interval";
    }
  }
  return {};
}

// The same for one dimension: one point in every interval of length 2^-k.
inline std::string netDefect1D(const std::vector<float>& points, int k) {
  std::vector<uint8_t> count(size_t{1} << k, 0);
  if (points.size() != count.size()) return "expected 2^" + std::to_string(k) + " points";
  for (float x : points)
    if (++count[static_cast<size_t>(std::ldexp(x, k))] > 1) return "two points in an interval";
  return {};
}

// Request `request` (counting next1D and next2D calls; earlier requests are 2-D) of samples
// [first, first + count) of one pixel.
template <class S>
Vec2 requestPoint(S& sampler, IVec2 pixel, uint32_t index, int request) {
  sampler.startPixelSample(pixel, index);
  for (int r = 0; r < request; ++r) sampler.next2D();
  return sampler.next2D();
}

template <class S>
std::vector<Vec2> pixelPoints(S& sampler, IVec2 pixel, int request, uint32_t first, uint32_t count) {
  std::vector<Vec2> out;
  out.reserve(count);
  for (uint32_t i = first; i < first + count; ++i) out.push_back(requestPoint(sampler, pixel, i, request));
  return out;
}

// The first `draws` pairs of requests (next2D, then next1D) of a pixel's sample, in order.
template <class S>
std::vector<float> sampleValues(S& s, IVec2 pixel, uint32_t index, int draws) {
  s.startPixelSample(pixel, index);
  std::vector<float> v;
  for (int d = 0; d < draws; ++d) {
    const Vec2 u = s.next2D();
    v.insert(v.end(), {u.x, u.y, s.next1D()});
  }
  return v;
}

// Where the arrays of n points (next2D(j, n), after one plain 2-D request) of a pixel's first 2^k
// samples fail to be nets: each sample's n points, all n 2^k points, and the plain request after
// the array. Empty when all are nets; n must be a power of two.
template <class S>
std::string arrayNetDefect(S& s, IVec2 pixel, uint32_t n, int k) {
  const int log2n = std::bit_width(n) - 1;
  std::vector<Vec2> all, after;
  for (uint32_t i = 0; i < (1u << k); ++i) {
    s.startPixelSample(pixel, i);
    s.next2D();
    std::vector<Vec2> one;
    for (uint32_t j = 0; j < n; ++j) one.push_back(s.next2D(j, n));
    if (std::string d = netDefect(one, log2n); !d.empty()) return "one sample's array: " + d;
    all.insert(all.end(), one.begin(), one.end());
    after.push_back(s.next2D());
  }
  if (std::string d = netDefect(all, k + log2n); !d.empty()) return "all arrays: " + d;
  if (std::string d = netDefect(after, k); !d.empty()) return "the request after: " + d;
  return {};
}

// Pearson correlation of paired values.
inline double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = static_cast<double>(a.size());
  double ma = 0, mb = 0;
  for (size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
  ma /= n, mb /= n;
  double sab = 0, saa = 0, sbb = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : 1.0;
}

// A smooth, non-separable test integrand on [0,1]^2 and its integral (sum of 1 / ((n+1)^2 n!)).
inline double smoothIntegrand(Vec2 u) {
  return std::exp(static_cast<double>(u.x) * u.y);
}
inline double smoothIntegral() {
  double sum = 0, factorial = 1;
  for (int n = 0; n < 30; ++n) {
    if (n > 0) factorial *= n;
    sum += 1.0 / ((n + 1.0) * (n + 1.0) * factorial);
  }
  return sum;
}

// The estimate of smoothIntegral from samples [0, count) of request `request` of one pixel.
template <class S>
double pixelEstimate(S& sampler, IVec2 pixel, int request, uint32_t count) {
  double sum = 0;
  for (uint32_t i = 0; i < count; ++i) sum += smoothIntegrand(requestPoint(sampler, pixel, i, request));
  return sum / count;
}

// Mean squared error of pixelEstimate over `pixels` pixels (each an independent replication for
// a sampler that decorrelates pixels).
template <class S>
double meanSquaredError(S& sampler, uint32_t count, int pixels) {
  const double exact = smoothIntegral();
  double sum = 0;
  for (int p = 0; p < pixels; ++p) {
    double e = pixelEstimate(sampler, IVec2(p % 97, 3 * (p / 97) + 1), 0, count) - exact;
    sum += e * e;
  }
  return sum / pixels;
}

// Least-squares slope of log MSE against log N for N = 2^kMin .. 2^kMax.
template <class S>
double mseSlope(S& sampler, int kMin, int kMax, int pixels) {
  std::vector<double> x, y;
  for (int k = kMin; k <= kMax; ++k) {
    x.push_back(k * std::log(2.0));
    y.push_back(std::log(meanSquaredError(sampler, 1u << k, pixels)));
  }
  double mx = 0, my = 0;
  for (size_t i = 0; i < x.size(); ++i) mx += x[i], my += y[i];
  mx /= x.size(), my /= y.size();
  double sxy = 0, sxx = 0;
  for (size_t i = 0; i < x.size(); ++i) sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx);
  return sxy / sxx;
}

}  // namespace penumbra
