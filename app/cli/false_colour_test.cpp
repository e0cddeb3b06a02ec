#include "app/cli/false_colour.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace penumbra::cli {
namespace {

void expectSame(const Rgb& a, const Rgb& b) {
  EXPECT_EQ(a.r, b.r);
  EXPECT_EQ(a.g, b.g);
  EXPECT_EQ(a.b, b.b);
}

TEST(FalseColour, EndsOfTheRamp) {
  expectSame(falseColour(0), Rgb{0.0, 0.0, 0.02});
  expectSame(falseColour(1), Rgb{0.99, 0.99, 0.75});
  const Rgb mid = falseColour(0.5);  // halfway between the third and fourth stops
  EXPECT_NEAR(mid.r, (0.55 + 0.87) / 2, 1e-12);
}

// Error maps of a run against a reference with infinite or NaN values give such t: each is a colour.
TEST(FalseColour, EveryDoubleIsAColourInRange) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expectSame(falseColour(nan), falseColour(0));
  expectSame(falseColour(-nan), falseColour(0));
  expectSame(falseColour(-inf), falseColour(0));
  expectSame(falseColour(-1e300), falseColour(0));
  expectSame(falseColour(inf), falseColour(1));
  expectSame(falseColour(1e300), falseColour(1));
  EXPECT_NEAR(falseColour(std::nextafter(1.0, 0.0)).b, 0.75, 1e-12);
  for (double t : {std::numeric_limits<double>::denorm_min(), 0.2, 0.4, 0.8, 0.999999}) {
    const Rgb c = falseColour(t);
    for (double v : {c.r, c.g, c.b}) EXPECT_TRUE(v >= 0 && v <= 1) << t;
  }
}

}  // namespace
}  // namespace penumbra::cli
