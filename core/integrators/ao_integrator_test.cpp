#include "core/integrators/ao_integrator.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/integrators/integrator_test_support.h"

namespace penumbra {
namespace {

using namespace test;  // the hand-built scenes

template <IntegratorDesc W>
Color3 sample(const Scene& scene, const Ray& ray, uint32_t index, int samples = 1) {
  Sampler sampler(SamplerKind::Independent, 1, 11);
  sampler.startPixelSample(IVec2(2, 9), index);
  return test::integratorOf<W>(samples).Li(scene, ray, sampler);
}

TEST(AoIntegrator, AnOpenPlaneIsUnoccludedAndAlbedoIsNotApplied) {
  auto scene = planeScene(10.f, Color3(0.25f));
  finish(*scene);
  // Cosine sampling: V cos / (π pdf) = 1 for every visible direction, so every sample is exactly 1.
  for (uint32_t i = 0; i < 256; ++i)
    ASSERT_EQ(sample<aoBy(HemisphereWarp::Cosine)>(*scene, rayDownOnto(0.1f, 0.2f), i), Color3(1.f)) << i;
  // Uniform sampling: 2 cos θ per sample, mean 1 and standard deviation 1/√3.
  const int n = 8192;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    float v = sample<aoBy(HemisphereWarp::Uniform)>(*scene, rayDownOnto(0.1f, 0.2f), uint32_t(i)).x;
    ASSERT_TRUE(v >= 0.f && v <= 2.f) << v;
    sum += v;
  }
  const double se = 1.0 / std::sqrt(3.0 * n);
  EXPECT_NEAR(sum / n, 1.0, 4 * se);
}

TEST(AoIntegrator, InsideAClosedSphereEverythingIsOccluded) {
  auto scene = planeScene(3.f);
  addSphere(*scene, Vec3(0.f), 5.f);
  finish(*scene);
  EXPECT_EQ(sample<aoBy(HemisphereWarp::Cosine)>(*scene, rayDownOnto(0, 0), 0, 64), Color3(0.f));
  EXPECT_EQ(sample<aoBy(HemisphereWarp::Uniform)>(*scene, rayDownOnto(0, 0), 0, 64), Color3(0.f));
}

TEST(AoIntegrator, ACameraRayThatMissesIsBlack) {
  auto scene = planeScene();
  finish(*scene);
  Ray up;
  up.o = Vec3(0, 0, 1);
  up.d = Vec3(0, 0, 1);
  EXPECT_EQ(sample<aoBy(HemisphereWarp::Cosine)>(*scene, up, 0), Color3(0.f));
}

// A sphere of radius 1 at height 3 straight above x blocks the cone of half-angle α (sin α = 1/3):
// AO = 1 − sin²α for both warps.
template <IntegratorDesc W>
void expectCapOccluded() {
  auto scene = planeScene();
  addSphere(*scene, Vec3(0, 0, 3), 1.f);
  finish(*scene);
  const int n = 40000;
  double sum = 0, sumSq = 0;
  for (int i = 0; i < n; ++i) {
    double v = sample<W>(*scene, rayDownOnto(0, 0), uint32_t(i)).x;
    sum += v;
    sumSq += v * v;
  }
  const double mean = sum / n, se = std::sqrt(std::max(0.0, sumSq / n - mean * mean) / (n - 1));
  EXPECT_GT(se, 0.0);
  EXPECT_NEAR(mean, 1.0 - 1.0 / 9.0, 4 * se);
}

TEST(AoIntegrator, CosineSamplingUnderASphereMatchesTheClosedForm) {
  expectCapOccluded<aoBy(HemisphereWarp::Cosine)>();
}

TEST(AoIntegrator, UniformSamplingUnderASphereMatchesTheClosedForm) {
  expectCapOccluded<aoBy(HemisphereWarp::Uniform)>();
}

}  // namespace
}  // namespace penumbra
