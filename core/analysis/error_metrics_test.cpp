#include "core/analysis/error_metrics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

Image filled(int w, int h, float v) {
  Image img(w, h);
  for (float& x : img.rgb) x = v;
  return img;
}

TEST(ErrorMetrics, ConstantOffset) {
  Image ref = filled(4, 3, 1.f), est = filled(4, 3, 1.5f);
  ErrorReport r = computeErrors(est, ref);
  EXPECT_DOUBLE_EQ(r.all.mse, 0.25);
  EXPECT_DOUBLE_EQ(r.all.rmse, 0.5);
  EXPECT_NEAR(r.all.relMse, 0.25 / 1.01, 1e-12);
  EXPECT_DOUBLE_EQ(r.all.mseStdErr, 0.0);
  EXPECT_EQ(r.all.pixels, 12u);
  EXPECT_EQ(r.noLight.pixels, 12u);
}

TEST(ErrorMetrics, MaskExcludesLitPixels) {
  Image ref = filled(2, 1, 0.f), est = filled(2, 1, 0.f);
  est.set(0, 0, Color3(10.f));  // a bright pixel with a large error
  est.set(1, 0, Color3(1.f));
  ErrorReport r = computeErrors(est, ref, {}, {1, 0});
  EXPECT_DOUBLE_EQ(r.all.mse, (100.0 + 1.0) / 2);
  EXPECT_DOUBLE_EQ(r.noLight.mse, 1.0);
  EXPECT_EQ(r.noLight.pixels, 1u);
  EXPECT_GT(r.all.mseStdErr, 0.0);
}

TEST(ErrorMetrics, SubtractsReferenceNoise) {
  // Estimate = truth exactly; reference = truth + noise of known standard error s:
  // raw MSE ~ s^2, and the corrected MSE is ~0 within its standard error.
  const int w = 200, h = 200;
  const double s = 0.1;
  Image truth = filled(w, h, 0.5f), ref(w, h), se = filled(w, h, float(s));
  uint64_t state = 12345;
  auto gauss = [&] {
    auto u = [&] {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      return (double(state >> 11) + 0.5) / 9007199254740992.0;
    };
    return std::sqrt(-2 * std::log(u())) * std::cos(2 * kPiD * u());
  };
  for (std::size_t i = 0; i < ref.rgb.size(); ++i) ref.rgb[i] = float(truth.rgb[i] + s * gauss());
  ErrorReport r = computeErrors(truth, ref, se);
  EXPECT_NEAR(r.all.rawMse, s * s, 4 * r.all.mseStdErr);
  EXPECT_NEAR(r.all.mse, 0.0, 4 * r.all.mseStdErr);
  EXPECT_NEAR(r.all.refVariance, s * s, 1e-8);  // s is stored as float
}

TEST(ErrorMetrics, SizeMismatchThrows) {
  EXPECT_ANY_THROW(computeErrors(filled(2, 2, 0.f), filled(3, 2, 0.f)));
  EXPECT_ANY_THROW(computeErrors(filled(2, 2, 0.f), filled(2, 2, 0.f), {}, {1, 0}));
}

TEST(ErrorMetrics, LogLogSlope) {
  std::vector<double> x{1, 10, 100, 1000}, y{1, 0.1, 0.01, 0.001};
  EXPECT_NEAR(logLogSlope(x, y), -1.0, 1e-12);
  EXPECT_TRUE(std::isnan(logLogSlope({1}, {1})));
}

}  // namespace
}  // namespace penumbra
