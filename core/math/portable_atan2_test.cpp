#include "core/math/portable_atan2.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

namespace penumbra {
namespace {

// |portableAtan2(y, x) − atan2(y, x)| in ulps of the result, against long double's atan2 (64-bit
// significand: exact to about a thousandth of a double ulp).
double ulpError(double y, double x) {
  const long double exact = std::atan2((long double)y, (long double)x);
  const double rounded = double(exact);
  const double ulp = std::nextafter(std::fabs(rounded), INFINITY) - std::fabs(rounded);
  return double(std::fabs((long double)portableAtan2(y, x) - exact) / ulp);
}

// Random arguments (the math layer's tests use the standard library's generator).
struct Draws {
  std::mt19937_64 engine{17};
  double unit() { return std::uniform_real_distribution<double>(0.0, 1.0)(engine); }
  bool coin() { return engine() % 2 == 0; }
  double symmetric() { return 2 * unit() - 1; }
  // Random sign, magnitude 2^e with e from −1000 to 1000.
  double anyMagnitude() {
    const double m = std::ldexp(1.0 + unit(), int(engine() % 2001) - 1000);
    return coin() ? m : -m;
  }
};

// Within 2.5 ulp of the exact value everywhere (2.03 the worst seen): ratios near 1 and near tan(π/8) (where
// the reduction switches), all four quadrants, magnitudes from 2^-1000 to 2^1000, and ratios beyond 2^±60.
TEST(PortableAtan2, IsWithinTwoAndAHalfUlpOfTheExactValue) {
  Draws rng;
  double worst = 0.0;
  for (int i = 0; i < 1000000; ++i) {
    double y, x;
    switch (i % 4) {
      case 0:
        y = rng.symmetric(), x = rng.symmetric();
        break;
      case 1:
        y = rng.anyMagnitude(), x = rng.anyMagnitude();
        break;
      case 2: {  // |y / x| near tan(π/8) or its inverse
        x = rng.symmetric();
        const double r = PortableAtan2::kTanPiOver8 * (1 + 1e-3 * rng.symmetric());
        y = x * (rng.coin() ? r : 1 / r) * (rng.coin() ? 1 : -1);
        break;
      }
      default: {  // |y / x| near 1
        x = rng.symmetric();
        y = x * (1 + 1e-6 * rng.symmetric()) * (rng.coin() ? 1 : -1);
      }
    }
    const double e = ulpError(y, x);
    worst = std::max(worst, e);
    ASSERT_LE(e, 2.5) << "atan2(" << y << ", " << x << ")";
  }
  EXPECT_GT(worst, 0.5) << worst;  // the measure sees rounding (it is not comparing a value with itself)
}

// atan2's special values: signed zeros and axes, infinities and NaN, as std::atan2 gives them.
TEST(PortableAtan2, KeepsAtan2sSignsZerosAndSpecialValues) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  const double values[] = {0.0, -0.0, 1.0, -1.0, 1e-310, -1e-310, 1e308, -1e308, inf, -inf};
  for (double y : values)
    for (double x : values) {
      SCOPED_TRACE("atan2(" + std::to_string(y) + ", " + std::to_string(x) + ")");
      const double got = portableAtan2(y, x), expected = std::atan2(y, x);
      EXPECT_EQ(std::signbit(got), std::signbit(expected));
      EXPECT_LE(std::fabs(got - expected), 4e-16 * std::fabs(expected));
    }
  EXPECT_TRUE(std::isnan(portableAtan2(nan, 1.0)));
  EXPECT_TRUE(std::isnan(portableAtan2(1.0, nan)));
  EXPECT_EQ(portableAtan2(0.0, -0.0), PortableAtan2::kPi);
  EXPECT_EQ(portableAtan2(1.0, 0.0), PortableAtan2::kPiOver2);
  EXPECT_EQ(portableAtan2(1e-300, 1.0), 1e-300);  // tiny angles keep full precision
}

}  // namespace
}  // namespace penumbra
