#include "core/lights/directional_light.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

TEST(DirectionalLight, SampleIsTowardTheLightAtInfiniteDistance) {
  // As in the assignment's sphere-directional.xml: direction (1, 1, 0) points toward the light,
  // above the y = −0.05 plane.
  DirectionalLight d = DirectionalLight::make(Vec3(1, 1, 0), Color3(2));
  DeltaLightSample ds = d.sample(Vec3(5, -0.05f, 3));
  EXPECT_NEAR(ds.wi.x, std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(ds.wi.y, std::sqrt(0.5f), 1e-6f);
  EXPECT_EQ(ds.wi.z, 0.f);
  EXPECT_GT(glm::dot(ds.wi, Vec3(0, 1, 0)), 0.f);  // lights the plane's upper side
  EXPECT_TRUE(std::isinf(ds.dist));
  EXPECT_EQ(ds.Li, Color3(2));
  // The same everywhere.
  DeltaLightSample other = d.sample(Vec3(-100, 7, 0));
  EXPECT_EQ(other.wi, ds.wi);
  EXPECT_EQ(other.Li, ds.Li);
}

TEST(DirectionalLight, MakeNormalisesAndAZeroDirectionFallsBackToPlusZ) {
  DirectionalLight d = DirectionalLight::make(Vec3(0, 0, -5), Color3(1));
  EXPECT_EQ(d.direction, Vec3(0, 0, -1));
  DirectionalLight z = DirectionalLight::make(Vec3(0), Color3(1));
  EXPECT_EQ(z.direction, Vec3(0, 0, 1));
}

}  // namespace
}  // namespace penumbra
