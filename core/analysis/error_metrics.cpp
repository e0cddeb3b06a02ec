#include "core/analysis/error_metrics.h"

#include <cmath>
#include <limits>

#include "core/math/error.h"

namespace penumbra {

namespace {

struct Accumulator {
  double sumSq = 0, sumSqSq = 0, sumRel = 0, sumVar = 0, sumRelVar = 0;
  std::size_t n = 0;

  ErrorStats finish() const {
    ErrorStats s;
    s.pixels = n;
    if (n == 0) return s;
    double N = double(n);
    s.rawMse = sumSq / N;
    s.refVariance = sumVar / N;
    s.mse = s.rawMse - s.refVariance;
    s.rmse = std::sqrt(std::max(s.mse, 0.0));
    s.relMse = (sumRel - sumRelVar) / N;
    double var = n > 1 ? std::max(0.0, (sumSqSq - sumSq * sumSq / N) / (N - 1)) : 0.0;
    s.mseStdErr = std::sqrt(var / N);
    return s;
  }
};

}  // namespace

ErrorReport computeErrors(const Image& estimate, const Image& reference, const Image& refStdErr,
                          const std::vector<uint8_t>& seesLight) {
  if (estimate.width != reference.width || estimate.height != reference.height)
    throw Error("error metrics: estimate is " + std::to_string(estimate.width) + "x" +
                std::to_string(estimate.height) + " but the reference is " + std::to_string(reference.width) +
                "x" + std::to_string(reference.height));
  bool haveErr = !refStdErr.empty();
  if (haveErr && (refStdErr.width != reference.width || refStdErr.height != reference.height))
    throw Error("error metrics: the reference's standard error image has the wrong size");
  std::size_t count = reference.pixelCount();
  if (!seesLight.empty() && seesLight.size() != count)
    throw Error("error metrics: the emitter mask has the wrong size");

  Accumulator all, dark;
  for (std::size_t p = 0; p < count; ++p) {
    double sq = 0, rel = 0, var = 0, relVar = 0;
    for (int c = 0; c < 3; ++c) {
      double r = reference.rgb[3 * p + c];
      double e = double(estimate.rgb[3 * p + c]) - r;
      double w = 1.0 / (r * r + 0.01);
      sq += e * e;
      rel += e * e * w;
      if (haveErr) {
        double s = refStdErr.rgb[3 * p + c];
        var += s * s;
        relVar += s * s * w;
      }
    }
    sq /= 3, rel /= 3, var /= 3, relVar /= 3;
    auto add = [&](Accumulator& a) {
      a.sumSq += sq;
      a.sumSqSq += sq * sq;
      a.sumRel += rel;
      a.sumVar += var;
      a.sumRelVar += relVar;
      ++a.n;
    };
    add(all);
    if (seesLight.empty() || !seesLight[p]) add(dark);
  }
  return {all.finish(), dark.finish()};
}

double logLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) {
    if (!(x[i] > 0) || !(y[i] > 0)) continue;
    double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
    ++n;
  }
  if (n < 2) return std::numeric_limits<double>::quiet_NaN();
  double den = n * sxx - sx * sx;
  if (den == 0) return std::numeric_limits<double>::quiet_NaN();
  return (n * sxy - sx * sy) / den;
}

}  // namespace penumbra
