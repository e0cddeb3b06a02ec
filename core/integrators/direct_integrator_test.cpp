#include "core/integrators/direct_integrator.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/integrators/test_scene_fixture.h"

namespace penumbra {
namespace {

using namespace test;  // the hand-built scenes

template <Strategy S>
Color3 once(const Scene& scene, const Ray& ray, uint64_t seed = 1) {
  Sampler sampler(SamplerKind::Independent, 1, seed);
  sampler.startPixelSample(IVec2(0), 0);
  return DirectIntegrator<S>{1}.Li(scene, ray, sampler);
}

// Mean and standard error of the red channel over n independent samples.
template <Strategy S>
std::pair<double, double> estimate(const Scene& scene, const Ray& ray, int n) {
  Sampler sampler(SamplerKind::Independent, 1, 7);
  double sum = 0, sumSq = 0;
  for (int i = 0; i < n; ++i) {
    sampler.startPixelSample(IVec2(3, 5), uint32_t(i));
    double v = DirectIntegrator<S>{1}.Li(scene, ray, sampler).x;
    sum += v;
    sumSq += v * v;
  }
  double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sumSq / n - mean * mean) / (n - 1))};
}

TEST(DirectIntegrator, PointLightGivesAlbedoOverPiTimesIntensityCosOverDistanceSquared) {
  auto scene = planeScene(10.f, Color3(0.5f));
  scene->pointLights.push_back(PointLight{Vec3(1, 0, 2), Color3(8)});
  finish(*scene);
  // d² = 5, cos θ = 2/√5.
  const double truth = 0.5 / M_PI * 8.0 / 5.0 * 2.0 / std::sqrt(5.0);
  EXPECT_NEAR(once<Strategy::Simple>(*scene, rayDownOnto(0, 0)).x, truth, 1e-6 * truth);
  // Without area lights every strategy is the delta-light sum.
  EXPECT_NEAR(once<Strategy::DirectSolidAngle>(*scene, rayDownOnto(0, 0)).x, truth, 1e-6 * truth);
  EXPECT_NEAR(once<Strategy::DirectCosineHemisphere>(*scene, rayDownOnto(0, 0)).x, truth, 1e-6 * truth);
}

TEST(DirectIntegrator, DirectionalLightGivesAlbedoOverPiTimesIrradianceCos) {
  auto scene = planeScene();
  scene->directionalLights.push_back(DirectionalLight::make(Vec3(0, 1, 1), Color3(2)));
  finish(*scene);
  const double truth = 2.0 * std::sqrt(0.5) / M_PI;
  EXPECT_NEAR(once<Strategy::Simple>(*scene, rayDownOnto(0.3f, -0.2f)).x, truth, 1e-6 * truth);
}

TEST(DirectIntegrator, OccludedOrBelowTheHorizonDeltaLightsGiveExactlyZero) {
  auto blocked = planeScene();
  blocked->pointLights.push_back(PointLight{Vec3(1, 0, 2), Color3(8)});
  addSphere(*blocked, Vec3(0.5f, 0, 1), 0.2f);  // on the segment from the origin to the light
  finish(*blocked);
  EXPECT_EQ(once<Strategy::Simple>(*blocked, rayDownOnto(0, 0)), Color3(0.f));

  auto below = planeScene();
  below->pointLights.push_back(PointLight{Vec3(0, 0, -2), Color3(8)});
  below->directionalLights.push_back(DirectionalLight::make(Vec3(0, 1, -1), Color3(2)));
  finish(*below);
  EXPECT_EQ(once<Strategy::Simple>(*below, rayDownOnto(0, 0)), Color3(0.f));
}

TEST(DirectIntegrator, ACameraRayOnTheLightSeesItsRadiance) {
  auto scene = planeScene();
  addSphere(*scene, Vec3(0, 0, 3), 1.f, Color3(5));
  finish(*scene);
  Ray ray;
  ray.o = Vec3(0, 0, 6);
  ray.d = Vec3(0, 0, -1);
  EXPECT_EQ(once<Strategy::DirectSolidAngle>(*scene, ray), Color3(5));
  EXPECT_EQ(once<Strategy::DirectArea>(*scene, ray), Color3(5));
}

// A sphere light of radius 1 at height 3 straight above, fully visible: E = π Le sin²α cos θ with
// sin α = 1/3, so Lr = albedo · Le / 9. Every strategy within 4 standard errors, and a 10 % error
// would be caught (the bound is tight enough to fail).
TEST(DirectIntegrator, EveryStrategyAgreesOnAFullyVisibleSphereLight) {
  auto scene = planeScene();
  addSphere(*scene, Vec3(0, 0, 3), 1.f, Color3(5));
  finish(*scene);
  const double truth = 5.0 / 9.0;
  const Ray ray = rayDownOnto(0, 0);
  constexpr int kN = 200000;
  for (auto [name, e] :
       {std::pair{"solid-angle", estimate<Strategy::DirectSolidAngle>(*scene, ray, kN)},
        std::pair{"area", estimate<Strategy::DirectArea>(*scene, ray, kN)},
        std::pair{"cosine", estimate<Strategy::DirectCosineHemisphere>(*scene, ray, kN)},
        std::pair{"uniform", estimate<Strategy::DirectUniformHemisphere>(*scene, ray, kN)}}) {
    auto [mean, se] = e;
    EXPECT_GT(se, 0.0) << name;
    EXPECT_NEAR(mean, truth, 4 * se) << name;
    EXPECT_GT(std::fabs(mean - 1.1 * truth), 4 * se) << name << ": the bound would not catch a 10 % bias";
  }
  // Delta-only ignores area lights.
  EXPECT_EQ(once<Strategy::Simple>(*scene, ray), Color3(0.f));
}

}  // namespace
}  // namespace penumbra
