#include "core/integrators/direct_integrator.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "core/integrators/integrator_test_support.h"

namespace penumbra {
namespace {

using test::Estimate;
using test::estimateAlong;

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
// 1e4 scale, with the independent and the stratified sampler.
TEST(DirectIntegrator, ProjectedSolidAngleHasZeroVarianceWhereUnoccluded) {
  const Vec3 x0(0.31f, 0.17f, 0.f);
  for (float scale : {1e-4f, 1.f, 1e4f})
    for (const LightCase& lc : kUnoccluded)
      for (SamplerKind kind : {SamplerKind::Independent, SamplerKind::Stratified}) {
        const Vec3 x = x0 * scale, c = (x0 + lc.offset) * scale;
        const float r = lc.r * scale;
        auto scene = test::planeScene({{c, r, lc.Le}}, 10.f * scale);
        const Ray ray = test::shallowRayOnto(x, scale);
        SurfaceHit hit;
        ASSERT_TRUE(scene->geometry.intersect(ray, hit));
        const double truth = test::closedFormRadiance(hit.p, c, r, lc.Le);
        ASSERT_GT(truth, 0.0) << lc.name;
        DirectIntegrator<DirectStrategy::ProjectedSolidAngle> psa{1};
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
  DirectIntegrator<DirectStrategy::ProjectedSolidAngle> psa{1};
  DirectIntegrator<DirectStrategy::SolidAngle> solid{1};
  const Estimate a = estimateAlong(*scene, psa, ray, 200000, 5);
  const Estimate b = estimateAlong(*scene, solid, ray, 200000, 6);
  const double unoccluded = test::closedFormRadiance(x, x + Vec3(0.4f, 0.f, 2.f), 0.5f, 10.f);
  EXPECT_LT(a.mean, 0.95 * unoccluded);  // the occluder casts a penumbra here
  EXPECT_GT(a.mean, 0.05 * unoccluded);
  EXPECT_NEAR(a.mean, b.mean, 4 * std::hypot(a.standardError, b.standardError));
}

}  // namespace
}  // namespace penumbra
