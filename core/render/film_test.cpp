#include "core/render/film.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

TEST(Film, MeanAndStandardErrorOfKnownSamples) {
  Film film(2, 1);
  for (float v : {1.f, 2.f, 3.f, 4.f}) film.add(1, 0, Color3(v, 2 * v, 0));
  Image mean = film.mean(4), se = film.standardError(4);
  EXPECT_FLOAT_EQ(mean.at(1, 0).x, 2.5f);
  EXPECT_FLOAT_EQ(mean.at(1, 0).y, 5.f);
  // sample variance of 1..4 is 5/3; standard error sqrt(5/3/4)
  EXPECT_NEAR(se.at(1, 0).x, std::sqrt(5.0 / 12.0), 1e-6);
  EXPECT_EQ(mean.at(0, 0).x, 0.f);

  Color3 m, e;  // one pixel's statistics agree with the whole-image resolves bit for bit
  film.pixelStatistics(4, 1, 0, m, e);
  EXPECT_EQ(m, mean.at(1, 0));
  EXPECT_EQ(e, se.at(1, 0));
  film.pixelStatistics(1, 1, 0, m, e);
  EXPECT_EQ(e, Color3(0.f));  // below two samples there is no estimate of the error
}

TEST(Film, AMillionSamplesInOnePixelDoNotDrift) {
  Film film(1, 1);
  const int n = 1000000;
  for (int i = 0; i < n; ++i) film.add(0, 0, Color3(0.1f + float(i % 3) * 1e-3f));
  // Exact mean of the float values added (0.1f, 0.101f, 0.102f repeating).
  double exact = (double(0.1f) + double(0.1f + 1e-3f) + double(0.1f + 2e-3f)) / 3.0;
  EXPECT_NEAR(film.mean(n).at(0, 0).x, exact, 1e-7);
}

}  // namespace
}  // namespace penumbra
