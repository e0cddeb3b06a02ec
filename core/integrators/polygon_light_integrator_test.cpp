// Polygon lights through the integrators: every light measure, MIS with each, hemisphere sampling and a
// light selection, against Lambert's closed form (the irradiance of a uniform polygon clipped to the
// horizon) on a receiver under each of the polygon configurations (above, straddling, grazing, tiny,
// sliver, huge, at three scales), with an independent and a low-discrepancy sampler; projected solid
// angle with zero variance; a density that does not match the samples fails the same bound.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "core/integrators/integrator_test_support.h"
#include "core/lights/polygon_lambert.h"
#include "core/lights/polygon_light_test_support.h"

namespace penumbra {
namespace {

using test::Config;
using test::Estimate;

constexpr float kRadiance = 3.f;

// The receiver (albedo 1) through c.x facing c.n, the polygon emitting towards it, and a camera ray
// straight onto c.x from between the receiver and the light.
struct PolygonScene {
  std::unique_ptr<Scene> scene;
  Ray ray;
  double truth = 0;  // (albedo / π) Le Ω⊥ at the point the ray hits
  double projectedSolidAngle = 0;
};

PolygonScene polygonScene(const Config& c) {
  std::vector<Vec3> v = c.vertices;
  const DVec3 v0(v[0]);
  const DVec3 nl = glm::cross(DVec3(v[1]) - v0, DVec3(v[2]) - v0);
  if (glm::dot(nl, DVec3(c.x) - v0) < 0) std::reverse(v.begin(), v.end());  // emit towards x
  double nearest = INFINITY;
  for (const Vec3& p : v) nearest = std::min(nearest, glm::length(DVec3(p) - DVec3(c.x)));
  const double planeDistance = std::abs(glm::dot(glm::normalize(nl), DVec3(c.x) - v0));

  PolygonScene out;
  out.scene = std::make_unique<Scene>();
  const Frame frame(c.n);
  const float half = float(1e3 * nearest);
  out.scene->geometry.addMesh(
      makeGridPlane(c.x - half * (frame.s + frame.t), 2.f * half * frame.s, 2.f * half * frame.t, 1, 1), 0);
  out.scene->materials.push_back(SurfaceMaterial{makeDiffuse(Color3(1.f))});
  test::addPolygonLight(*out.scene, v, Color3(kRadiance));
  test::finish(*out.scene);

  const float h = float(std::min(0.5 * planeDistance, 1e-3 * nearest));
  out.ray.o = c.x + h * c.n;
  out.ray.d = -c.n;
  SurfaceHit hit;
  EXPECT_TRUE(out.scene->geometry.intersect(out.ray, hit)) << c.name;
  EXPECT_EQ(hit.objectId, 0u) << c.name;
  out.projectedSolidAngle = polygonLightIrradianceFactor(DVec3(hit.p), DVec3(c.n), test::toDouble(v));
  out.truth = kRadiance / kPiD * out.projectedSolidAngle;
  return out;
}

template <IntegratorDesc D>
Estimate estimate(const PolygonScene& s, SamplerKind kind, int n = 16384) {
  return test::estimateAlong(*s.scene, test::integratorOf<D>(1), s.ray, n, 5, kind);
}

bool verbose() {
  return std::getenv("PENUMBRA_VERBOSE") != nullptr;
}

// Within 4.5 standard errors (Šidák over the ~500 estimates here at a 1 % family-wise level needs
// 4.0) plus float rounding of the truth, plus `unseen` · truth: the share of the estimate that comes
// from events too rare for the sample count to see (and so to show in the standard error).
void expectUnbiased(const Estimate& e, double truth, const std::string& what, double unseen = 0) {
  if (verbose())
    std::printf("%-60s truth %.8g mean %.8g SE %.3g\n", what.c_str(), truth, e.mean, e.standardError);
  EXPECT_EQ(e.bad, 0u) << what;
  EXPECT_NEAR(e.mean, truth, 4.5 * e.standardError + (1e-6 + unseen) * truth) << what;
}

constexpr SamplerKind kSamplers[] = {SamplerKind::Independent, SamplerKind::ZSobol};

TEST(PolygonLightIntegrator, EveryLightMeasureIsUnbiasedAgainstLambertsClosedForm) {
  for (const Config& c : test::polygonConfigs()) {
    const PolygonScene s = polygonScene(c);
    ASSERT_GT(s.truth, 0.0) << c.name;
    // Cosine directions meet the light with probability Ω⊥ / π: below ~50 expected hits their share
    // of an MIS estimate (at most Ω⊥ / π of it) may go unseen.
    constexpr int kN = 16384;
    const double hitChance = s.projectedSolidAngle / kPiD;
    const double unseenMis = kN * hitChance < 50 ? hitChance : 0;
    for (SamplerKind kind : kSamplers) {
      const std::string at = std::string(c.name) + " " + samplerKindName(kind) + " ";
      // A polygon so large that its light crowds into a spot a 1e-8 of its area: area samples find the
      // spot too rarely for any sample count here (the configuration binned on the disk).
      if (c.binOnThePolygon)
        expectUnbiased(estimate<directByLight(LightMeasure::Area)>(s, kind), s.truth, at + "area");
      expectUnbiased(estimate<directByLight(LightMeasure::SolidAngle)>(s, kind), s.truth, at + "solid-angle");
      expectUnbiased(estimate<directByLight(LightMeasure::SolidAngle, LightSelection::Bvh)>(s, kind), s.truth,
                     at + "solid-angle, bvh");
      expectUnbiased(estimate<directByMis(LightMeasure::Area, MisHeuristic::Balance)>(s, kind), s.truth,
                     at + "mis/area", unseenMis);
      expectUnbiased(estimate<directByMis(LightMeasure::SolidAngle, MisHeuristic::Power)>(s, kind), s.truth,
                     at + "mis/solid-angle", unseenMis);
      expectUnbiased(estimate<directByMis(LightMeasure::ProjectedSolidAngle, MisHeuristic::Balance)>(s, kind),
                     s.truth, at + "mis/projected-solid-angle", unseenMis);
      // Hemisphere sampling finds the light by tracing; too rarely for the tiny ones to be measured.
      if (kN * hitChance > 300)
        expectUnbiased(estimate<directByHemisphere(HemisphereWarp::Cosine)>(s, kind), s.truth, at + "cosine");
    }
  }
}

// Every camera sample's estimate is (albedo/π) Le Ω⊥ to float rounding, with every sampler: above,
// straddling, grazing, tiny, huge, at 1e-3 and 1e3 scale.
TEST(PolygonLightIntegrator, ProjectedSolidAngleHasZeroVarianceWhereUnoccluded) {
  for (const Config& c : test::polygonConfigs()) {
    const PolygonScene s = polygonScene(c);
    for (SamplerKind kind : test::everySampler()) {
      const Estimate psa = estimate<directByLight(LightMeasure::ProjectedSolidAngle)>(s, kind, 4096);
      const Estimate bvh =
          estimate<directByLight(LightMeasure::ProjectedSolidAngle, LightSelection::Bvh)>(s, kind, 4096);
      if (verbose())
        std::printf("%-28s %-11s truth %.9g samples in [%.9g, %.9g]\n", c.name, samplerKindName(kind),
                    s.truth, psa.minValue, psa.maxValue);
      for (const Estimate& e : {psa, bvh}) {
        EXPECT_EQ(e.bad, 0u) << c.name;
        EXPECT_NEAR(e.minValue, s.truth, 2e-6 * s.truth) << c.name << " " << samplerKindName(kind);
        EXPECT_NEAR(e.maxValue, s.truth, 2e-6 * s.truth) << c.name << " " << samplerKindName(kind);
      }
    }
  }
}

// Solid-angle samples divided by the area density: the bound above rejects it wherever cos θ varies
// over the light enough for the sample count to see.
TEST(PolygonLightIntegrator, AMismatchedDensityFailsTheBound) {
  int detectable = 0;
  for (const Config& c : test::polygonConfigs()) {
    if (!c.solidAnglePdfDetectable) continue;
    ++detectable;
    const PolygonScene s = polygonScene(c);
    const PolygonLight& light = s.scene->polygonLights.at(0);
    SurfaceHit hit;
    ASSERT_TRUE(s.scene->geometry.intersect(s.ray, hit));
    const ShadingPoint sp(*s.scene, s.ray, hit);
    const LightTechnique<LightMeasure::SolidAngle, PolygonLight> technique(light, sp);
    ASSERT_TRUE(technique.canSample()) << c.name;
    Sampler sampler(SamplerKind::Independent, 1, 3);
    double sum = 0, sumSq = 0;
    constexpr int kN = 16384;
    for (int i = 0; i < kN; ++i) {
      sampler.startPixelSample(IVec2(1, 2), uint32_t(i));
      const LightSample ls = technique.sample(sampler.next2D());
      const float cosTheta = glm::dot(sp.ns, ls.wi);
      const double v = ls.pdf > 0 && cosTheta > 0
                           ? kRadiance / kPiD * cosTheta / light.pdfAreaAsSolidAngle(sp.hit.p, ls.p)
                           : 0.0;
      sum += v;
      sumSq += v * v;
    }
    const double mean = sum / kN, se = std::sqrt(std::max(0.0, sumSq / kN - mean * mean) / (kN - 1));
    EXPECT_GT(std::abs(mean - s.truth), 4.5 * se + 1e-6 * s.truth) << c.name << ": the wrong density passes";
  }
  EXPECT_GE(detectable, 8);
}

}  // namespace
}  // namespace penumbra
