#include "core/integrators/ao_integrator.h"

#include <gtest/gtest.h>

#include "core/integrators/integrator_test_scene.h"

namespace penumbra {
namespace {

using test::estimateOnTop;
using test::Moments;
using test::receiverScene;

Scene openScene() {
  Scene s = receiverScene();
  s.geometry.build(AccelMode::BruteForce);
  return s;
}

// Nothing above the top of a convex receiver: AO = 1. Cosine sampling weighs every sample 1, so the
// estimate is exactly 1; uniform sampling weighs it 2 cos θ, whose mean is 1.
TEST(AoIntegrator, CosineSamplingOfAnUnoccludedPointIsExactlyOne) {
  Scene scene = openScene();
  Moments m = estimateOnTop(scene, AoIntegrator<Strategy::AoCosine>{4}, 256, 5);
  EXPECT_EQ(m.bad, 0u);
  EXPECT_DOUBLE_EQ(m.mean, 1.0);
}

TEST(AoIntegrator, UniformSamplingOfAnUnoccludedPointAveragesToOne) {
  Scene scene = openScene();
  Moments m = estimateOnTop(scene, AoIntegrator<Strategy::AoUniform>{1}, 40000, 6);
  EXPECT_EQ(m.bad, 0u);
  EXPECT_GT(m.standardError, 0.0);
  EXPECT_NEAR(m.mean, 1.0, 4.0 * m.standardError);
}

// A sphere of radius r at distance d straight above x blocks the cone of half-angle α (sin α = r/d):
// AO = 1 − sin²α, with the same value for both warps.
template <Strategy kStrategy>
void expectCapOccluded() {
  Scene s = receiverScene();
  s.geometry.addSphere(Sphere{Vec3(0.f, 0.f, 3.f), 1.f}, 1);
  s.materials.push_back(SurfaceMaterial{Color3(0.5f), -1});
  s.geometry.build(AccelMode::BruteForce);
  Moments m = estimateOnTop(s, AoIntegrator<kStrategy>{1}, 40000, 7);
  EXPECT_EQ(m.bad, 0u);
  EXPECT_NEAR(m.mean, 1.0 - 1.0 / 4.0, 4.0 * m.standardError) << "±" << m.standardError;
}

TEST(AoIntegrator, CosineSamplingUnderASphereMatchesTheClosedForm) {
  expectCapOccluded<Strategy::AoCosine>();
}

TEST(AoIntegrator, UniformSamplingUnderASphereMatchesTheClosedForm) {
  expectCapOccluded<Strategy::AoUniform>();
}

}  // namespace
}  // namespace penumbra
