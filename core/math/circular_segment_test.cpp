#include "core/math/circular_segment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace penumbra {
namespace {

constexpr long double kPiL = 3.141592653589793238462643383279502884L;

// g(β) = β − sin β cos β in long double: the series Σ (−1)^(k+1) (2β)^(2k+1) / (2 (2k+1)!) below 0.3.
long double segmentAreaL(long double beta) {
  if (beta > 0.3L) return beta - sinl(beta) * cosl(beta);
  const long double b2 = 4 * beta * beta;
  long double power = 2 * beta, factorial = 1, sum = 0;
  for (int k = 1; k < 20; ++k) {
    power *= b2;
    factorial *= (2 * k) * (2 * k + 1);
    sum += (k % 2 ? 1 : -1) * power / (2 * factorial);
  }
  return sum;
}

// Areas from 1e-300 to π: log-spaced below π/2, uniform over [0, π], and the ends.
std::vector<double> testAreas() {
  std::vector<double> areas;
  for (int i = 0; i <= 30000; ++i) areas.push_back(1.5707963267948966 * std::pow(10.0, -300.0 * i / 30000.0));
  for (int i = 1; i < 100000; ++i) areas.push_back(3.141592653589793 * i / 100000.0);
  for (double e : {1e-16, 1e-12, 1e-8, 1e-4}) {
    areas.push_back(1.5707963267948966 * (1 - e));
    areas.push_back(1.5707963267948966 * (1 + e));
    areas.push_back(3.141592653589793 * (1 - e));
  }
  return areas;
}

TEST(CircularSegment, SinCosHalfPiMatchesTheLibrary) {
  double worst = 0;
  for (int i = 0; i <= 200000; ++i) {
    const double x = 1.5707963267948966 * i / 200000.0;
    const SinCosD sc = sinCosHalfPi(x);
    worst = std::max({worst, double(std::fabs(sc.sin - sinl(x))), double(std::fabs(sc.cos - cosl(x)))});
  }
  EXPECT_LT(worst, 4e-16);
}

TEST(CircularSegment, AreaIsRelativelyAccurate) {
  double worst = 0;
  for (int i = 0; i <= 100000; ++i) {
    const double beta = 3.141592653589793 * std::pow(10.0, -12.0 * i / 100000.0);
    const long double truth = segmentAreaL(beta);
    const double area = segmentArea(beta, SinCosD{std::sin(beta), std::cos(beta)});
    worst = std::max(worst, double(std::fabs((area - truth) / truth)));
  }
  EXPECT_LT(worst, 1e-14);
}

// The inverse's stated accuracy: g at the returned angle is within 5e-13 of the area, relative to the
// area (beyond π/2: to π − area, plus the 1e-15 to which double represents π − area).
TEST(CircularSegment, AngleInvertsTheArea) {
  double worstArea = 0, worstUnit = 0;
  for (const double area : testAreas()) {
    const SinCosD sc = segmentAngle(area);
    ASSERT_TRUE(sc.sin >= 0 && sc.sin <= 1 && sc.cos >= -1 && sc.cos <= 1) << area;
    const long double beta = atan2l(sc.sin, sc.cos);
    const long double scale = std::min<long double>(area, kPiL - area);
    const long double error = std::fabs(segmentAreaL(beta) - area);
    ASSERT_LE(error, 5e-13L * scale + (area > 1.5707963267948966 ? 1e-15L : 0.0L)) << "area " << area;
    if (area <= 1.5707963267948966) worstArea = std::max(worstArea, double(error / scale));
    worstUnit = std::max(worstUnit,
                         double(std::fabs(sc.sin * (long double)sc.sin + sc.cos * (long double)sc.cos - 1)));
  }
  std::printf("worst relative area error (area <= pi/2) %.3g, worst |sin^2 + cos^2 - 1| %.3g\n", worstArea,
              worstUnit);
  EXPECT_LT(worstUnit, 1e-15);
}

TEST(CircularSegment, AngleIsMonotoneInTheArea) {
  double lastCos = 2;
  for (int i = 0; i <= 200000; ++i) {
    const SinCosD sc = segmentAngle(3.141592653589793 * i / 200000.0);
    ASSERT_LE(sc.cos, lastCos) << i;  // β increases: cos β decreases
    lastCos = sc.cos;
  }
}

TEST(CircularSegment, EndsAndNonFiniteInput) {
  EXPECT_EQ(segmentAngle(0.0).sin, 0.0);
  EXPECT_EQ(segmentAngle(0.0).cos, 1.0);
  EXPECT_EQ(segmentAngle(-1.0).cos, 1.0);
  EXPECT_EQ(segmentAngle(NAN).cos, 1.0);
  EXPECT_EQ(segmentAngle(4.0).cos, -1.0);
  EXPECT_EQ(segmentAngle(INFINITY).cos, -1.0);
  const SinCosD half = segmentAngle(1.5707963267948966);
  EXPECT_NEAR(half.cos, 0.0, 1e-15);
  EXPECT_NEAR(half.sin, 1.0, 1e-15);
  const SinCosD tiny = segmentAngle(1e-310);  // subnormal: β = ∛(3t/2)
  EXPECT_NEAR(tiny.sin / std::cbrt(1.5e-310), 1.0, 1e-12);
}

}  // namespace
}  // namespace penumbra
