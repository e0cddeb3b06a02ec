#include "core/integrators/direct_integrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/integrators/integrator_test_support.h"

namespace penumbra {
namespace {

using namespace test;  // the hand-built scenes

template <IntegratorDesc S>
Color3 once(const Scene& scene, const Ray& ray, uint64_t seed = 1) {
  Sampler sampler(SamplerKind::Independent, 1, seed);
  sampler.startPixelSample(IVec2(0), 0);
  return test::integratorOf<S>(1).Li(scene, ray, sampler);
}

// Mean and standard error of the red channel over n independent samples.
template <IntegratorDesc S>
std::pair<double, double> estimate(const Scene& scene, const Ray& ray, int n) {
  Sampler sampler(SamplerKind::Independent, 1, 7);
  double sum = 0, sumSq = 0;
  for (int i = 0; i < n; ++i) {
    sampler.startPixelSample(IVec2(3, 5), uint32_t(i));
    double v = test::integratorOf<S>(1).Li(scene, ray, sampler).x;
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
  const double truth = 0.5 / kPiD * 8.0 / 5.0 * 2.0 / std::sqrt(5.0);
  EXPECT_NEAR(once<integratorOfType(IntegratorType::Simple)>(*scene, rayDownOnto(0, 0)).x, truth,
              1e-6 * truth);
  // Without area lights every strategy is the delta-light sum.
  EXPECT_NEAR(once<directByLight(LightMeasure::SolidAngle)>(*scene, rayDownOnto(0, 0)).x, truth,
              1e-6 * truth);
  EXPECT_NEAR(once<directByHemisphere(HemisphereWarp::Cosine)>(*scene, rayDownOnto(0, 0)).x, truth,
              1e-6 * truth);
}

TEST(DirectIntegrator, DirectionalLightGivesAlbedoOverPiTimesIrradianceCos) {
  auto scene = planeScene();
  scene->directionalLights.push_back(DirectionalLight::make(Vec3(0, 1, 1), Color3(2)));
  finish(*scene);
  const double truth = 2.0 * std::sqrt(0.5) / kPiD;
  EXPECT_NEAR(once<integratorOfType(IntegratorType::Simple)>(*scene, rayDownOnto(0.3f, -0.2f)).x, truth,
              1e-6 * truth);
}

TEST(DirectIntegrator, OccludedOrBelowTheHorizonDeltaLightsGiveExactlyZero) {
  auto blocked = planeScene();
  blocked->pointLights.push_back(PointLight{Vec3(1, 0, 2), Color3(8)});
  addSphere(*blocked, Vec3(0.5f, 0, 1), 0.2f);  // on the segment from the origin to the light
  finish(*blocked);
  EXPECT_EQ(once<integratorOfType(IntegratorType::Simple)>(*blocked, rayDownOnto(0, 0)), Color3(0.f));

  auto below = planeScene();
  below->pointLights.push_back(PointLight{Vec3(0, 0, -2), Color3(8)});
  below->directionalLights.push_back(DirectionalLight::make(Vec3(0, 1, -1), Color3(2)));
  finish(*below);
  EXPECT_EQ(once<integratorOfType(IntegratorType::Simple)>(*below, rayDownOnto(0, 0)), Color3(0.f));
}

TEST(DirectIntegrator, ACameraRayOnTheLightSeesItsRadiance) {
  auto scene = planeScene();
  addSphere(*scene, Vec3(0, 0, 3), 1.f, Color3(5));
  finish(*scene);
  Ray ray;
  ray.o = Vec3(0, 0, 6);
  ray.d = Vec3(0, 0, -1);
  EXPECT_EQ(once<directByLight(LightMeasure::SolidAngle)>(*scene, ray), Color3(5));
  EXPECT_EQ(once<directByLight(LightMeasure::Area)>(*scene, ray), Color3(5));
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
       {std::pair{"solid-angle", estimate<directByLight(LightMeasure::SolidAngle)>(*scene, ray, kN)},
        std::pair{"area", estimate<directByLight(LightMeasure::Area)>(*scene, ray, kN)},
        std::pair{"cosine", estimate<directByHemisphere(HemisphereWarp::Cosine)>(*scene, ray, kN)},
        std::pair{"uniform", estimate<directByHemisphere(HemisphereWarp::Uniform)>(*scene, ray, kN)}}) {
    auto [mean, se] = e;
    EXPECT_GT(se, 0.0) << name;
    EXPECT_NEAR(mean, truth, 4 * se) << name;
    EXPECT_GT(std::fabs(mean - 1.1 * truth), 4 * se) << name << ": the bound would not catch a 10 % bias";
  }
  // Projected solid angle has no variance here: one sample is the closed form up to float rounding.
  EXPECT_NEAR(once<directByLight(LightMeasure::ProjectedSolidAngle)>(*scene, ray).x, truth, 1e-6 * truth);
  // Delta-only ignores area lights.
  EXPECT_EQ(once<integratorOfType(IntegratorType::Simple)>(*scene, ray), Color3(0.f));
}

// A light relative to the shading point x on the plane z = 0 (coordinates in units of `scale`).
struct LightCase {
  const char* name;
  Vec3 offset;  // centre − x
  float r;
  float Le;
};

const LightCase kUnoccluded[] = {
    {"above", Vec3(0.5f, 0.2f, 2.f), 0.5f, 10.f},
    {"overhead", Vec3(0.f, 0.f, 3.f), 1.f, 1.f},
    {"straddling", Vec3(1.5f, 0.f, 0.3f), 0.6f, 5.f},
    {"straddlingBelow", Vec3(1.5f, 0.4f, -0.3f), 0.6f, 5.f},
    {"centreOnHorizon", Vec3(2.f, 0.f, 0.f), 0.5f, 5.f},
    {"grazing89_9", Vec3(2.f * std::cos(0.0017453f), 0.f, 2.f * std::sin(0.0017453f)), 0.3f, 5.f},
    {"tinyDistant", Vec3(300.f, 100.f, 800.f), 0.01f, 1e7f},
    {"veryTinyDistant", Vec3(0.f, 3000.f, 4000.f), 0.005f, 1e9f},
    {"tinyStraddling", Vec3(0.f, 500.f, 0.005f), 0.01f, 1e7f},
    {"justOutsideSurface", Vec3(0.f, 0.f, 1.000001f), 1.f, 1.f},
};

// Projected-solid-angle sampling of an unoccluded light: every camera sample's estimate is the closed
// form (albedo/π) Le Ω⊥ up to float rounding — zero variance — in every configuration, at 1e-4 and
// 1e4 scale, with every sampler.
TEST(DirectIntegrator, ProjectedSolidAngleHasZeroVarianceWhereUnoccluded) {
  const Vec3 x0(0.31f, 0.17f, 0.f);
  for (float scale : {1e-4f, 1.f, 1e4f})
    for (const LightCase& lc : kUnoccluded)
      for (SamplerKind kind : test::everySampler()) {
        const Vec3 x = x0 * scale, c = (x0 + lc.offset) * scale;
        const float r = lc.r * scale;
        auto scene = test::planeScene({{c, r, lc.Le}}, 10.f * scale);
        const Ray ray = test::shallowRayOnto(x, scale);
        SurfaceHit hit;
        ASSERT_TRUE(scene->geometry.intersect(ray, hit));
        const double truth = test::closedFormRadiance(hit.p, c, r, lc.Le);
        ASSERT_GT(truth, 0.0) << lc.name;
        const auto psa = test::integratorOf<directByLight(LightMeasure::ProjectedSolidAngle)>(1);
        const Estimate e = estimateAlong(*scene, psa, ray, 4000, 3, kind);
        if (std::getenv("PENUMBRA_VERBOSE"))
          std::printf("%-20s scale %g %-11s truth %.9g  samples in [%.9g, %.9g]  SE %.3g\n", lc.name, scale,
                      samplerKindName(kind), truth, e.minValue, e.maxValue, e.standardError);
        EXPECT_EQ(e.bad, 0u);
        // Every sample, not only the mean: float rounding of Le Ω⊥ albedo / π.
        EXPECT_NEAR(e.minValue, truth, 1e-6 * truth) << lc.name << " scale " << scale;
        EXPECT_NEAR(e.maxValue, truth, 1e-6 * truth) << lc.name << " scale " << scale;
      }
}

// Where part of the light is occluded, projected-solid-angle sampling is not zero-variance but
// unbiased: against solid-angle sampling of the same half-shadowed point (both within 4 SE).
TEST(DirectIntegrator, ProjectedSolidAngleIsUnbiasedInAPenumbra) {
  const Vec3 x(0.31f, 0.17f, 0.f);
  auto scene =
      test::planeScene({{x + Vec3(0.4f, 0.f, 2.f), 0.5f, 10.f}, {x + Vec3(0.12f, 0.f, 0.6f), 0.1f, 0.f}});
  const Ray ray = test::shallowRayOnto(x);
  const auto psa = test::integratorOf<directByLight(LightMeasure::ProjectedSolidAngle)>(1);
  const auto solid = test::integratorOf<directByLight(LightMeasure::SolidAngle)>(1);
  const Estimate a = estimateAlong(*scene, psa, ray, 200000, 5);
  const Estimate b = estimateAlong(*scene, solid, ray, 200000, 6);
  const double unoccluded = test::closedFormRadiance(x, x + Vec3(0.4f, 0.f, 2.f), 0.5f, 10.f);
  EXPECT_LT(a.mean, 0.95 * unoccluded);  // the occluder casts a penumbra here
  EXPECT_GT(a.mean, 0.05 * unoccluded);
  EXPECT_NEAR(a.mean, b.mean, 4 * std::hypot(a.standardError, b.standardError));
}

}  // namespace
}  // namespace penumbra
