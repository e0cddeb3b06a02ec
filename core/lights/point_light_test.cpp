#include "core/lights/point_light.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

TEST(PointLight, SampleGivesTheUnitDirectionDistanceAndInverseSquareRadiance) {
  PointLight p{Vec3(0, 0, 2), Color3(8)};
  DeltaLightSample s = p.sample(Vec3(0));
  EXPECT_EQ(s.wi, Vec3(0, 0, 1));
  EXPECT_FLOAT_EQ(s.dist, 2.f);
  EXPECT_FLOAT_EQ(s.Li.x, 2.f);  // I / d²
  // Off axis: d² = 3² + 4² = 25.
  DeltaLightSample t = p.sample(Vec3(3, 4, 2));
  EXPECT_FLOAT_EQ(t.dist, 5.f);
  EXPECT_NEAR(t.wi.x, -0.6f, 1e-6f);
  EXPECT_NEAR(t.wi.y, -0.8f, 1e-6f);
  EXPECT_FLOAT_EQ(t.Li.x, 8.f / 25.f);
}

TEST(PointLight, AShadingPointAtTheLightGetsNoLightAndNoNaN) {
  PointLight p{Vec3(0, 0, 2), Color3(8)};
  DeltaLightSample s = p.sample(Vec3(0, 0, 2));
  EXPECT_TRUE(isBlack(s.Li));
  EXPECT_FALSE(std::isnan(s.wi.x) || std::isnan(s.dist));
  // So far away that d² overflows: no light rather than 0 · Inf.
  DeltaLightSample far = p.sample(Vec3(3e19f, 0, 0));
  EXPECT_TRUE(isBlack(far.Li));
}

}  // namespace
}  // namespace penumbra
