// Every estimator (every strategy of the direct integrator, AO with both warps) with every sampler
// against the closed forms of core/analysis/closed_forms.h, with a statistical bound: |estimate -
// truth| < 4 standard errors of the estimate (plus a tiny absolute slack for float rounding when the
// truth is exactly representable; samplers other than independent take their standard error from
// seeded replications, core/render/ray_estimator.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "core/analysis/closed_forms.h"
#include "core/analysis/ray_estimate.h"
#include "core/render/strategy_axes.h"
#include "core/render/strategy_dispatch.h"
#include "core/sampling/sampler_table.h"
#include "core/scene/scene_builder.h"

namespace penumbra {
namespace {

using analysis::Estimate;
using analysis::rayOnto;

// A diffuse plane z = 0 (albedo 1, half-size `planeHalf`) and one sphere light.
// (pbrt's conservative triangle test, which we use, rejects very shallow hits on huge triangles,
// so the plane is kept moderate: its size does not enter the closed form for receivers on it.)
LoadedScene planeAndLight(const Vec3& c, float r, float Le, float planeHalf = 10.f) {
  std::ostringstream xml;
  xml.precision(9);
  xml << "<scene><integrator type=\"direct\"/>"
      << "<shape type=\"plane\"><bsdf type=\"diffuse\"><color name=\"albedo\" value=\"1\"/></bsdf>"
      << "<transform name=\"toWorld\"><scale value=\"" << planeHalf << ",1," << planeHalf << "\"/>"
      << "<rotate axis=\"1,0,0\" angle=\"90\"/></transform></shape>"
      << "<shape type=\"sphere\"><point name=\"center\" value=\"" << c.x << "," << c.y << "," << c.z << "\"/>"
      << "<float name=\"radius\" value=\"" << r
      << "\"/><emitter type=\"area\"><color name=\"radiance\" value=\"" << Le
      << "\"/></emitter></shape></scene>";
  return loadSceneFromString(xml.str(), "test.xml", ".");
}

using analysis::shallowRayOnto;

// The estimator of `strategy`, one shading sample per camera sample, with one sampler (the tests
// below run every sampler of the table).
Estimate directAt(const IntegratorDesc& strategy, const LoadedScene& s, const Vec3& x, int n, uint64_t seed,
                  SamplerKind sampler = SamplerKind::Independent) {
  return estimateRayOf(withSamples(strategy, 1), *s.scene, shallowRayOnto(x), n, seed, sampler);
}

struct LightCase {
  const char* name;
  Vec3 c;
  float r;
  float Le;
  bool hemisphereToo;   // hemisphere sampling of tiny lights has (correctly) enormous variance
  bool areaToo = true;  // so has area sampling a light 1e-6 r away: only a tiny cap of it is visible
};

void checkAgainstTruth(const char* what, const Estimate& e, double truth) {
  EXPECT_EQ(e.bad, 0u) << what;
  // Slack for float rounding and for estimators whose samples are (almost) all equal.
  double tolerance = 4.0 * e.standardError + 1e-5 * std::fabs(truth);
  EXPECT_NEAR(e.mean, truth, tolerance) << what << ": estimate " << e.mean << " ± " << e.standardError;
}

class DirectClosedForm : public ::testing::TestWithParam<LightCase> {};

TEST_P(DirectClosedForm, EveryMeasureMatchesTheIrradianceClosedForm) {
  const LightCase& lc = GetParam();
  // x is off the plane's diagonal (the shared edge of its two triangles); lights are placed relative to it.
  const Vec3 x(0.31f, 0.17f, 0.f);
  LoadedScene s = planeAndLight(x + lc.c, lc.r, lc.Le);
  // Lr = albedo/pi * Le * I(theta, alpha), albedo = 1, at the point and normal the integrator shades: the
  // shallow camera ray meets the (float-rotated) plane up to 1e-4 away from x, which the zero-variance
  // projected-solid-angle estimate resolves.
  SurfaceHit hit;
  ASSERT_TRUE(s.scene->geometry.intersect(shallowRayOnto(x), hit));
  double truth =
      lc.Le / kPiD *
      sphereLightIrradianceFactor(glm::dvec3(hit.p), glm::dvec3(hit.ns),
                                  glm::dvec3(s.scene->sphereLights[0].sphere.center), double(lc.r));
  const int n = 40000;
  for (const SamplerRow& sampler : samplerTable())
    for (uint64_t seed : {1u, 2u}) {
      SCOPED_TRACE(std::string(sampler.label));
      const SamplerKind kind = sampler.kind;
      // Every light measure, every light per sample.
      for (const LightMeasureRow& m : kLightMeasures) {
        if (!lc.areaToo && m.measure == LightMeasure::Area) continue;
        checkAgainstTruth(std::string(m.spellings.canonical()).c_str(),
                          directAt(directByLight(m.measure), s, x, n, seed, kind), truth);
      }
      // Unoccluded: projected-solid-angle sampling's every sample is the closed form (zero variance).
      const Estimate psa = directAt(directByLight(LightMeasure::ProjectedSolidAngle), s, x, n, seed, kind);
      EXPECT_LE(psa.standardError, 1e-6 * truth) << "projected-solid-angle";
      // Every MIS strategy (light measure x heuristic, one light and one cosine sample per camera sample).
      for (const IntegratorDesc& d : everyStrategyOfType(integratorOfType(IntegratorType::Direct))) {
        if (!d.usesMisAxes()) continue;
        if (!lc.areaToo && d.lightMeasure == LightMeasure::Area) continue;
        checkAgainstTruth(strategyLabel(d).c_str(), directAt(d, s, x, n, seed, kind), truth);
      }
      if (lc.hemisphereToo) {
        checkAgainstTruth("cosine-hemisphere",
                          directAt(directByHemisphere(HemisphereWarp::Cosine), s, x, 4 * n, seed, kind),
                          truth);
        checkAgainstTruth("uniform-hemisphere",
                          directAt(directByHemisphere(HemisphereWarp::Uniform), s, x, 4 * n, seed, kind),
                          truth);
      }
    }
}

INSTANTIATE_TEST_SUITE_P(
    Lights, DirectClosedForm,
    ::testing::Values(LightCase{"above", Vec3(0.5f, 0.2f, 2.f), 0.5f, 10.f, true},
                      LightCase{"overhead", Vec3(0.f, 0.f, 3.f), 1.f, 1.f, true},
                      LightCase{"straddling", Vec3(1.5f, 0.f, 0.3f), 0.6f, 5.f, true},
                      LightCase{"centreOnHorizon", Vec3(2.f, 0.f, 0.f), 0.5f, 5.f, true},
                      LightCase{"grazing89_9",
                                Vec3(2.f * std::cos(0.0017453f), 0.f, 2.f * std::sin(0.0017453f)), 0.3f, 5.f,
                                true},
                      LightCase{"tinyDistant", Vec3(300.f, 100.f, 800.f), 0.01f, 1e7f, false},
                      LightCase{"veryTinyDistant", Vec3(0.f, 3000.f, 4000.f), 0.005f, 1e9f, false},
                      LightCase{"justOutsideSurface", Vec3(0.f, 0.f, 1.000001f), 1.f, 1.f, true, false},
                      LightCase{"belowHorizon", Vec3(0.f, 2.f, -1.5f), 1.f, 1.f, true}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(DirectClosedForm, LightBelowTheHorizonGivesExactlyZero) {
  LoadedScene s = planeAndLight(Vec3(0, 2, -1.5f), 1.f, 100.f);
  std::vector<IntegratorDesc> strategies = {directByHemisphere(HemisphereWarp::Uniform)};
  for (const LightMeasureRow& m : kLightMeasures) strategies.push_back(directByLight(m.measure));
  for (const SamplerRow& sampler : samplerTable())
    for (const IntegratorDesc& strategy : strategies) {
      const Estimate e = directAt(strategy, s, Vec3(0), 1000, 3, sampler.kind);
      EXPECT_EQ(e.mean, 0.0) << strategyLabel(strategy) << ", " << sampler.label;
      EXPECT_EQ(e.bad, 0u);
    }
}

// ---- one light per sample: every light selection is unbiased --------------------------------------

// Several sphere lights of different power in different directions from the receivers (none hides
// another from them), one straddling the horizon and one below it: the truth is the sum of each
// light's closed form.
struct SeveralLights {
  LoadedScene scene;
  std::vector<std::pair<Vec3, float>> lights;  // centre, radius
  std::vector<float> radiance;
};

SeveralLights severalLights() {
  SeveralLights out;
  out.lights = {{Vec3(0.5f, 0.2f, 2.f), 0.5f},  {Vec3(-3.f, 1.f, 2.5f), 0.3f}, {Vec3(2.f, -3.f, 1.f), 0.8f},
                {Vec3(1.5f, 2.5f, 0.3f), 0.6f}, {Vec3(-1.f, -4.f, 4.f), 0.2f}, {Vec3(0.f, 3.f, -1.5f), 1.f}};
  out.radiance = {10.f, 40.f, 2.f, 5.f, 80.f, 100.f};
  std::ostringstream xml;
  xml.precision(9);
  xml << "<scene><integrator type=\"direct\"/>"
      << "<shape type=\"plane\"><bsdf type=\"diffuse\"><color name=\"albedo\" value=\"1\"/></bsdf>"
      << "<transform name=\"toWorld\"><scale value=\"10,1,10\"/><rotate axis=\"1,0,0\" "
         "angle=\"90\"/></transform></shape>";
  for (size_t i = 0; i < out.lights.size(); ++i) {
    const Vec3& c = out.lights[i].first;
    xml << "<shape type=\"sphere\"><point name=\"center\" value=\"" << c.x << "," << c.y << "," << c.z
        << "\"/><float name=\"radius\" value=\"" << out.lights[i].second
        << "\"/><emitter type=\"area\"><color name=\"radiance\" value=\"" << out.radiance[i]
        << "\"/></emitter></shape>";
  }
  xml << "</scene>";
  out.scene = loadSceneFromString(xml.str(), "lights.xml", ".");
  return out;
}

constexpr int kSelectionCameraSamples = 50000;

TEST(DirectClosedForm, EveryLightSelectionMatchesTheSumOfTheLightsClosedForms) {
  const SeveralLights s = severalLights();
  ASSERT_EQ(s.scene.scene->sphereLights.size(), 6u);
  // Every light-sampling strategy (each light measure with all, uniform, power, bvh).
  std::vector<IntegratorDesc> strategies;
  for (const IntegratorDesc& d : everyStrategyOfType(integratorOfType(IntegratorType::Direct)))
    if (d.usesLightSelection()) strategies.push_back(d);
  ASSERT_EQ(strategies.size(), kLightMeasures.size() * kLightSelections.size());
  for (const Vec3 x : {Vec3(0.31f, 0.17f, 0.f), Vec3(-2.1f, 0.4f, 0.f), Vec3(-0.8f, -1.f, 0.f)}) {
    // The truth at the point and normal the integrator shades (the shallow camera ray meets the plane
    // up to 1e-4 from x), which the all-lights projected-solid-angle estimate resolves.
    SurfaceHit hit;
    ASSERT_TRUE(s.scene.scene->geometry.intersect(shallowRayOnto(x), hit));
    double truth = 0.0;
    for (size_t i = 0; i < s.lights.size(); ++i)
      truth += s.radiance[i] / M_PI *
               sphereLightIrradianceFactor(glm::dvec3(hit.p), glm::dvec3(hit.ns),
                                           glm::dvec3(s.lights[i].first), double(s.lights[i].second));
    for (const IntegratorDesc& strategy : strategies)
      for (const SamplerRow& sampler : samplerTable()) {
        const std::string what =
            strategyLabel(strategy) + " at " + std::to_string(x.x) + ", " + std::string(sampler.label);
        // Independent: one shading sample per camera sample. The others: 4 per camera sample, so the
        // choice of the light and the point on it are two interleaved array requests of 4 points.
        const bool independent = sampler.kind == SamplerKind::Independent;
        const Estimate e =
            estimateRayOf(withSamples(strategy, independent ? 1 : 4), *s.scene.scene, shallowRayOnto(x),
                          independent ? 400000 : kSelectionCameraSamples, 4, sampler.kind);
        if (std::getenv("PENUMBRA_VERBOSE"))
          std::printf("%-40s est %.6g ± %.3g truth %.6g (SE %.2f %% of truth)\n", what.c_str(), e.mean,
                      e.standardError, truth, 100 * e.standardError / truth);
        checkAgainstTruth(what.c_str(), e, truth);
        // The test's power: independent must catch a 10 % bias; the others, with half the shading
        // samples, 15 % (area-power's rare large samples keep their error near independent's; a
        // misaligned request is off by far more).
        const double bias = independent ? 0.10 : 0.15;
        EXPECT_GT(std::fabs(e.mean - (1.0 + bias) * truth), 4 * e.standardError)
            << what << ": would not catch a " << 100 * bias << " % bias";
      }
  }
}

// ---- ambient occlusion --------------------------------------------------------------------------

// A sphere of radius R resting on the plane z = 0 at the origin.
// The plane's half-size matters only for points on the sphere (the closed form assumes an infinite
// plane); ray offsets scale with the plane's extent, so points on the plane use a smaller one.
LoadedScene restingSphere(float R, float planeHalf = 2000.f) {
  std::ostringstream xml;
  xml.precision(9);
  xml << "<scene><integrator type=\"ao\"/>"
      << "<shape type=\"plane\"><transform name=\"toWorld\"><scale value=\"" << planeHalf << ",1,"
      << planeHalf << "\"/>"
      << "<rotate axis=\"1,0,0\" angle=\"90\"/></transform></shape>"
      << "<shape type=\"sphere\"><point name=\"center\" value=\"0,0," << R
      << "\"/><float name=\"radius\" value=\"" << R << "\"/></shape></scene>";
  return loadSceneFromString(xml.str(), "ao.xml", ".");
}

Estimate aoAt(const IntegratorDesc& strategy, const LoadedScene& s, const Ray& ray, int n, uint64_t seed,
              SamplerKind sampler = SamplerKind::Independent) {
  return estimateRayOf(withSamples(strategy, 1), *s.scene, ray, n, seed, sampler);
}

TEST(AoClosedForm, PlaneNextToARestingSphere) {
  const float R = 1.f;
  LoadedScene s = restingSphere(R, 20.f);
  for (float rho : {0.05f, 0.3f, 1.f, 2.5f}) {
    double truth = aoPlaneNearRestingSphere(rho, R);
    // Look straight down onto the plane point (rho, 0, 0) from just above it.
    Ray ray = rayOnto(Vec3(rho, 0, 0), Vec3(0, 0, 1), 1e-3f);
    for (const SamplerRow& sampler : samplerTable()) {
      SCOPED_TRACE(std::string(sampler.label));
      checkAgainstTruth("ao uniform", aoAt(aoBy(HemisphereWarp::Uniform), s, ray, 100000, 5, sampler.kind),
                        truth);
      checkAgainstTruth("ao cosine", aoAt(aoBy(HemisphereWarp::Cosine), s, ray, 100000, 6, sampler.kind),
                        truth);
    }
  }
}

// The closed form assumes an infinite plane; the test's plane is a square of half-size L, so the
// nearly horizontal downward directions that pass its edge before reaching z = 0 are unoccluded too:
// (1/pi) * integral over azimuth of max(0, n . w(phi)) * atan(h / D(phi)), D the distance to the
// edge along phi, h the height above the plane (exact to O((h/D)^2), ~3e-4 at h = 1, L = 2000,
// which the Sobol' samplers resolve).
double finitePlaneEscape(const Vec3& p, const Vec3& n, double L) {
  const int steps = 4096;
  double sum = 0;
  for (int k = 0; k < steps; ++k) {
    double phi = (k + 0.5) * 2 * M_PI / steps, c = std::cos(phi), sn = std::sin(phi);
    double cosine = n.x * c + n.y * sn;
    if (cosine <= 0) continue;
    double dx = std::fabs(c) > 0 ? ((c > 0 ? L - p.x : L + p.x) / std::fabs(c)) : INFINITY;
    double dy = std::fabs(sn) > 0 ? ((sn > 0 ? L - p.y : L + p.y) / std::fabs(sn)) : INFINITY;
    sum += cosine * std::atan(p.z / std::min(dx, dy));
  }
  return sum * (2 * M_PI / steps) / M_PI;
}

TEST(AoClosedForm, PointsOnARestingSphere) {
  const float R = 1.f;
  LoadedScene s = restingSphere(R);
  for (float psiDeg : {0.f, 45.f, 90.f, 135.f, 170.f}) {
    double psi = psiDeg * kPiD / 180.0;
    Vec3 n(float(std::sin(psi)), 0.f, float(std::cos(psi)));
    Vec3 p = Vec3(0, 0, R) + R * n;
    double truth = aoOnRestingConvexBody(psi) + finitePlaneEscape(p, n, 2000.0);
    Ray ray = rayOnto(p, n, 0.01f);
    for (const SamplerRow& sampler : samplerTable()) {
      SCOPED_TRACE(std::string(sampler.label));
      checkAgainstTruth("ao uniform", aoAt(aoBy(HemisphereWarp::Uniform), s, ray, 100000, 7, sampler.kind),
                        truth);
      checkAgainstTruth("ao cosine", aoAt(aoBy(HemisphereWarp::Cosine), s, ray, 100000, 8, sampler.kind),
                        truth);
    }
  }
}

TEST(AoClosedForm, ACameraRayThatMissesIsBlack) {
  LoadedScene s = restingSphere(1.f);
  Ray ray;
  ray.o = Vec3(0, 0, 5);
  ray.d = Vec3(0, 0, 1);
  Estimate e = aoAt(aoBy(HemisphereWarp::Cosine), s, ray, 100, 1);
  EXPECT_EQ(e.mean, 0.0);
}

}  // namespace
}  // namespace penumbra
