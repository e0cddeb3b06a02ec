#include "core/integrators/mis_integrator.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "core/integrators/direct_integrator.h"
#include "core/integrators/integrator_test_support.h"

namespace penumbra {
namespace {

// The cosine-hemisphere density, the BSDF technique's on a diffuse surface.
float cosineDensity(float cosTheta) {
  return cosTheta * kInvPi;
}

using test::Estimate;
using test::estimateAlong;

const Vec3 kX(0.31f, 0.17f, 0.f);

// Scenes: one light in various places, a light half hidden by an occluder, two lights.
std::unique_ptr<Scene> sceneNamed(int i) {
  switch (i) {
    case 0:
      return test::planeScene({{kX + Vec3(0.5f, 0.2f, 2.f), 0.5f, 10.f}});
    case 1:
      return test::planeScene({{kX + Vec3(1.5f, 0.f, 0.3f), 0.6f, 5.f}});
    case 2:
      return test::planeScene(
          {{kX + Vec3(0.4f, 0.f, 2.f), 0.5f, 10.f}, {kX + Vec3(0.12f, 0.f, 0.6f), 0.1f, 0.f}});
    default:
      return test::planeScene(
          {{kX + Vec3(0.5f, 0.2f, 2.f), 0.5f, 10.f}, {kX + Vec3(0.2f, -1.5f, 0.3f), 0.6f, 5.f}});
  }
}
constexpr int kSceneCount = 4;

// Every camera sample of a with b, bit for bit.
template <class A, class B>
void expectSameSamples(const Scene& scene, const A& a, const B& b, const char* what, SamplerKind kind) {
  const Ray ray = test::shallowRayOnto(kX);
  Sampler sa(kind, 64, 9), sb(kind, 64, 9);
  int differing = 0, nonZero = 0;
  for (uint32_t i = 0; i < 2000; ++i) {
    sa.startPixelSample(IVec2(3, 4), i);
    sb.startPixelSample(IVec2(3, 4), i);
    const Color3 la = a.Li(scene, ray, sa), lb = b.Li(scene, ray, sb);
    differing += la != lb;
    nonZero += la.x > 0.f;
  }
  EXPECT_EQ(differing, 0) << what;
  EXPECT_GT(nonZero, 40) << what;  // cosine sampling reaches these lights in 3-5 % of its samples
}

template <LightMeasure kMeasure, IntegratorDesc kPlain, MisHeuristic kHeuristic>
void expectReductions(const Scene& scene, SamplerKind kind) {
  for (int count : {1, 3}) {
    expectSameSamples(scene, MisIntegrator<kMeasure, kHeuristic>{count, 0}, test::integratorOf<kPlain>(count),
                      "no hemisphere samples: light sampling", kind);
    expectSameSamples(scene, MisIntegrator<kMeasure, kHeuristic>{0, count},
                      test::integratorOf<directByHemisphere(HemisphereWarp::Cosine)>(count),
                      "no light samples: cosine", kind);
  }
}

TEST(MisIntegrator, AZeroCountReducesExactlyToTheOtherTechnique) {
  for (int i = 0; i < kSceneCount; ++i) {
    auto scene = sceneNamed(i);
    for (SamplerKind kind : test::everySampler()) {
      expectReductions<LightMeasure::Area, directByLight(LightMeasure::Area), MisHeuristic::Balance>(*scene,
                                                                                                     kind);
      expectReductions<LightMeasure::SolidAngle, directByLight(LightMeasure::SolidAngle),
                       MisHeuristic::Power>(*scene, kind);
      expectReductions<LightMeasure::ProjectedSolidAngle, directByLight(LightMeasure::ProjectedSolidAngle),
                       MisHeuristic::Balance>(*scene, kind);
      expectReductions<LightMeasure::ProjectedSolidAngle, directByLight(LightMeasure::ProjectedSolidAngle),
                       MisHeuristic::Power>(*scene, kind);
    }
  }
}

TEST(MisWeight, HeuristicsAndTheirLimits) {
  EXPECT_FLOAT_EQ(misWeight<MisHeuristic::Balance>(3.f, 1.f), 0.75f);
  EXPECT_FLOAT_EQ(misWeight<MisHeuristic::Power>(3.f, 1.f), 0.9f);
  EXPECT_EQ(misWeight<MisHeuristic::Balance>(2.f, 0.f), 1.f);
  EXPECT_EQ(misWeight<MisHeuristic::Power>(2.f, 0.f), 1.f);
  // Densities near float's limit neither overflow nor give NaN.
  EXPECT_EQ(misWeight<MisHeuristic::Power>(3e38f, 1.f), 1.f);
  EXPECT_EQ(misWeight<MisHeuristic::Power>(1.f, 3e38f), 0.f);
  EXPECT_FLOAT_EQ(misWeight<MisHeuristic::Balance>(3e38f, 3e38f), 0.5f);
}

// For every direction both techniques can produce, the two weights the integrator computes for it —
// one when the light technique sampled it (from the sample's pdf), one when the hemisphere technique
// did (from the light technique's pdf function at the point the direction reaches) — sum to 1. This
// ties the light samplers' returned pdfs to their pdf functions, the way MIS needs them.
template <LightMeasure kMeasure, MisHeuristic kHeuristic>
struct WeightCheck {
  using Mis = MisIntegrator<kMeasure, kHeuristic>;
  double worst = 0;  // largest |w_L + w_B − 1|
  int directions = 0;

  // The hemisphere technique's view of direction w: the light it reaches and where (if any).
  static bool reach(const Scene& scene, const ShadingPoint& sp, const Vec3& w, int32_t& light,
                    SurfaceHit& hit) {
    if (!scene.geometry.intersect(sp.spawnRay(w, INFINITY), hit)) return false;
    light = scene.materials[hit.objectId].sphereLight;
    return light >= 0;
  }

  // lightPdf: the light technique's density of w as the integrator evaluates it; a wrong one (the test
  // of the test) may be passed instead.
  template <class LightPdf>
  void run(const Scene& scene, float nL, float nB, LightPdf lightPdf) {
    const Ray ray = test::shallowRayOnto(kX);
    SurfaceHit hit;
    ASSERT_TRUE(scene.geometry.intersect(ray, hit));
    const ShadingPoint sp(scene, ray, hit);
    Sampler sampler(SamplerKind::Independent, 1, 4);
    for (uint32_t i = 0; i < 20000; ++i) {
      sampler.startPixelSample(IVec2(0), i);
      // Directions the light technique produced.
      for (size_t l = 0; l < scene.sphereLights.size(); ++l) {
        const LightTechnique<kMeasure, SphereLight> technique(scene.sphereLights[l], sp);
        const Vec2 u = sampler.next2D();
        if (!technique.canSample()) continue;
        const LightSample s = technique.sample(u);
        const float cosTheta = glm::dot(sp.ns, s.wi);
        if (!(s.pdf > 0.f) || isBlack(s.Le) || !leavesSurface(sp, s.wi, cosTheta)) continue;
        int32_t reached;
        SurfaceHit lh;
        if (!reach(scene, sp, s.wi, reached, lh) || reached != int32_t(l)) continue;  // occluded: weightless
        const float wL = misWeight<kHeuristic>(nL * s.pdf, nB * cosineDensity(cosTheta));
        const float wB = misWeight<kHeuristic>(nB * cosineDensity(cosTheta),
                                               nL * lightPdf(scene.sphereLights[l], sp, s.wi, lh));
        worst = std::max(worst, std::fabs(double(wL) + wB - 1.0));
        ++directions;
      }
      // Directions the hemisphere technique produced that reach a light.
      const Vec3 local = Warp::squareToCosineHemisphere(sampler.next2D());
      const Vec3 w = sp.frame.toWorld(local);
      int32_t reached;
      SurfaceHit lh;
      if (!(local.z > 0.f) || !leavesSurface(sp, w, local.z) || !reach(scene, sp, w, reached, lh)) continue;
      const SphereLight& light = scene.sphereLights[reached];
      if (isBlack(light.eval(lh.p, lh.ng, w))) continue;
      const float pL = lightPdf(light, sp, w, lh);
      const float wB = misWeight<kHeuristic>(nB * cosineDensity(local.z), nL * pL);
      // The light technique's weight for w, from the same density (its sampler returns it for w, as the
      // first half checks).
      const float wL =
          pL > 0.f ? misWeight<kHeuristic>(nL * pL, nB * cosineDensity(glm::dot(sp.ns, w))) : 0.f;
      worst = std::max(worst, std::fabs(double(wL) + wB - 1.0));
      ++directions;
    }
  }
};

template <LightMeasure kMeasure, MisHeuristic kHeuristic>
void expectWeightsSumToOne(const Scene& scene, const char* what) {
  WeightCheck<kMeasure, kHeuristic> check;
  for (auto [nL, nB] : {std::pair{1.f, 1.f}, std::pair{4.f, 1.f}, std::pair{1.f, 3.f}})
    check.run(scene, nL, nB,
              [](const SphereLight& l, const ShadingPoint& sp, const Vec3& w, const SurfaceHit& h) {
                return MisIntegrator<kMeasure, kHeuristic>::lightPdf(l, sp, w, h.p, h.ng);
              });
  EXPECT_GT(check.directions, 10000) << what;
  // Float rounding of the densities: the area one, d² / |cos θp|, is ill-conditioned near the
  // silhouette, where the re-intersected point differs from the sampled one by a float ulp.
  EXPECT_LT(check.worst, 1e-3) << what;
}

TEST(MisIntegrator, WeightsOfBothTechniquesSumToOne) {
  for (int i = 0; i < kSceneCount; ++i) {
    auto scene = sceneNamed(i);
    SCOPED_TRACE(i);
    expectWeightsSumToOne<LightMeasure::Area, MisHeuristic::Balance>(*scene, "area balance");
    expectWeightsSumToOne<LightMeasure::Area, MisHeuristic::Power>(*scene, "area power");
    expectWeightsSumToOne<LightMeasure::SolidAngle, MisHeuristic::Balance>(*scene, "solid-angle balance");
    expectWeightsSumToOne<LightMeasure::SolidAngle, MisHeuristic::Power>(*scene, "solid-angle power");
    expectWeightsSumToOne<LightMeasure::ProjectedSolidAngle, MisHeuristic::Balance>(*scene, "psa balance");
    expectWeightsSumToOne<LightMeasure::ProjectedSolidAngle, MisHeuristic::Power>(*scene, "psa power");
  }
}

// The test of the test: weighing projected-solid-angle samples with the solid-angle density (or area
// samples with the cone's) breaks the partition of unity.
TEST(MisIntegrator, WeightsFromAMismatchedDensityDoNotSumToOne) {
  auto scene = sceneNamed(1);
  WeightCheck<LightMeasure::ProjectedSolidAngle, MisHeuristic::Balance> psa;
  psa.run(*scene, 1.f, 1.f,
          [](const SphereLight& l, const ShadingPoint& sp, const Vec3& w, const SurfaceHit&) {
            return l.pdfSolidAngle(sp.hit.p, w);
          });
  EXPECT_GT(psa.worst, 0.05);
  WeightCheck<LightMeasure::Area, MisHeuristic::Power> area;
  area.run(*scene, 1.f, 1.f,
           [](const SphereLight& l, const ShadingPoint& sp, const Vec3& w, const SurfaceHit&) {
             return l.pdfSolidAngle(sp.hit.p, w);
           });
  EXPECT_GT(area.worst, 0.05);
}

// Against the closed form (within 4 standard errors): every light measure and heuristic, several
// counts, lights above, straddling and grazing the horizon and next to the shading point.
struct ClosedFormCase {
  const char* name;
  Vec3 offset;
  float r, Le;
};

template <LightMeasure kMeasure, MisHeuristic kHeuristic>
void expectClosedForm(const Scene& scene, double truth, const char* name, const char* what) {
  for (auto [nL, nB] : {std::pair{1, 1}, std::pair{2, 1}, std::pair{1, 4}})
    for (SamplerKind kind : test::everySampler()) {
      const MisIntegrator<kMeasure, kHeuristic> mis{nL, nB};
      const Estimate e = estimateAlong(scene, mis, test::shallowRayOnto(kX), 40000, 1 + nL + 7 * nB, kind);
      if (std::getenv("PENUMBRA_VERBOSE"))
        std::printf("%-20s %-22s %d+%d %-11s est %.7g ± %.2g truth %.7g (%.2f SE)\n", name, what, nL, nB,
                    samplerKindName(kind), e.mean, e.standardError, truth,
                    (e.mean - truth) / std::max(e.standardError, 1e-300));
      EXPECT_EQ(e.bad, 0u);
      EXPECT_NEAR(e.mean, truth, 4 * e.standardError + 1e-5 * truth)
          << name << " " << what << " " << nL << "+" << nB << " " << samplerKindName(kind);
    }
}

TEST(MisIntegrator, MatchesTheIrradianceClosedForm) {
  const ClosedFormCase cases[] = {
      {"above", Vec3(0.5f, 0.2f, 2.f), 0.5f, 10.f},
      {"straddling", Vec3(1.5f, 0.f, 0.3f), 0.6f, 5.f},
      {"centreOnHorizon", Vec3(2.f, 0.f, 0.f), 0.5f, 5.f},
      {"grazing89_9", Vec3(2.f * std::cos(0.0017453f), 0.f, 2.f * std::sin(0.0017453f)), 0.3f, 5.f},
      {"justOutsideSurface", Vec3(0.f, 0.f, 1.000001f), 1.f, 1.f},
  };
  for (const ClosedFormCase& c : cases) {
    auto scene = test::planeScene({{kX + c.offset, c.r, c.Le}});
    SurfaceHit hit;
    ASSERT_TRUE(scene->geometry.intersect(test::shallowRayOnto(kX), hit));
    const double truth = test::closedFormRadiance(hit.p, kX + c.offset, c.r, c.Le);
    if (std::string(c.name) != "justOutsideSurface") {  // area sampling sees 5e-7 of the light there
      expectClosedForm<LightMeasure::Area, MisHeuristic::Balance>(*scene, truth, c.name, "area balance");
      expectClosedForm<LightMeasure::Area, MisHeuristic::Power>(*scene, truth, c.name, "area power");
    }
    expectClosedForm<LightMeasure::SolidAngle, MisHeuristic::Balance>(*scene, truth, c.name,
                                                                      "solid-angle balance");
    expectClosedForm<LightMeasure::SolidAngle, MisHeuristic::Power>(*scene, truth, c.name,
                                                                    "solid-angle power");
    expectClosedForm<LightMeasure::ProjectedSolidAngle, MisHeuristic::Balance>(*scene, truth, c.name,
                                                                               "psa balance");
    expectClosedForm<LightMeasure::ProjectedSolidAngle, MisHeuristic::Power>(*scene, truth, c.name,
                                                                             "psa power");
  }
}

}  // namespace
}  // namespace penumbra
