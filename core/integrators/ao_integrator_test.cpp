#include "core/integrators/ao_integrator.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/integrators/test_scene_fixture.h"

namespace penumbra {
namespace {

using namespace test;  // the hand-built scenes

template <HemisphereWarp W>
Color3 sample(const Scene& scene, const Ray& ray, uint32_t index, int samples = 1) {
  Sampler sampler(SamplerKind::Independent, 1, 11);
  sampler.startPixelSample(IVec2(2, 9), index);
  return AoIntegrator<W>{samples}.Li(scene, ray, sampler);
}

TEST(AoIntegrator, AnOpenPlaneIsUnoccludedAndAlbedoIsNotApplied) {
  auto scene = planeScene(10.f, Color3(0.25f));
  finish(*scene);
  // Cosine sampling: V cos / (π pdf) = 1 for every visible direction, so every sample is exactly 1.
  for (uint32_t i = 0; i < 256; ++i)
    ASSERT_EQ(sample<HemisphereWarp::Cosine>(*scene, rayDownOnto(0.1f, 0.2f), i), Color3(1.f)) << i;
  // Uniform sampling: 2 cos θ per sample, mean 1 and standard deviation 1/√3.
  const int n = 8192;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    float v = sample<HemisphereWarp::Uniform>(*scene, rayDownOnto(0.1f, 0.2f), uint32_t(i)).x;
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
  EXPECT_EQ(sample<HemisphereWarp::Cosine>(*scene, rayDownOnto(0, 0), 0, 64), Color3(0.f));
  EXPECT_EQ(sample<HemisphereWarp::Uniform>(*scene, rayDownOnto(0, 0), 0, 64), Color3(0.f));
}

TEST(AoIntegrator, ACameraRayThatMissesIsBlack) {
  auto scene = planeScene();
  finish(*scene);
  Ray up;
  up.o = Vec3(0, 0, 1);
  up.d = Vec3(0, 0, 1);
  EXPECT_EQ(sample<HemisphereWarp::Cosine>(*scene, up, 0), Color3(0.f));
}

}  // namespace
}  // namespace penumbra
