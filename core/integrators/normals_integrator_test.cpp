#include "core/integrators/normals_integrator.h"

#include <gtest/gtest.h>

#include "core/integrators/integrator_test_support.h"

namespace penumbra {
namespace {

TEST(NormalsIntegrator, TheAbsoluteShadingNormalOrBlackOnAMiss) {
  auto scene = test::planeScene();
  test::addSphere(*scene, Vec3(5, 0, 2), 1.f);
  test::finish(*scene);
  Sampler sampler(SamplerKind::Independent, 1, 1);
  sampler.startPixelSample(IVec2(0), 0);
  NormalsIntegrator normals;
  EXPECT_EQ(normals.Li(*scene, test::rayDownOnto(0, 0), sampler), Color3(0, 0, 1));
  // The sphere's side facing -x: normal (-1, 0, 0), shown as (1, 0, 0).
  Ray side;
  side.o = Vec3(0, 0, 2);
  side.d = Vec3(1, 0, 0);
  Color3 n = normals.Li(*scene, side, sampler);
  EXPECT_NEAR(n.x, 1.f, 1e-5f);
  EXPECT_NEAR(n.y, 0.f, 1e-5f);
  EXPECT_NEAR(n.z, 0.f, 1e-5f);
  Ray up;
  up.o = Vec3(0, 0, 1);
  up.d = Vec3(0, 0, 1);
  EXPECT_EQ(normals.Li(*scene, up, sampler), Color3(0.f));
}

}  // namespace
}  // namespace penumbra
