// The stiff-case catalogue must pass as a whole (run once here; `penumbra check` runs the same code),
// and it must be able to fail: deliberately broken variants (a pdf off by 2×, a wrong expected value,
// a NaN sample, a wrong error message, a missing scene) are caught.
#include "core/analysis/stiff_cases.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "core/analysis/closed_forms.h"
#include "core/analysis/ray_estimate.h"
#include "core/integrators/shading_point.h"
#include "core/scene/scene_builder.h"

namespace penumbra::analysis {
namespace {

CaseOptions options() {
  CaseOptions o;
  o.sceneDir = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/stiff";
  return o;
}

TEST(StiffCases, EveryCategoryHasCasesAndNamesAreUnique) {
  std::set<std::string> categories, names;
  for (const StiffCase& c : stiffCases()) {
    categories.insert(c.category);
    EXPECT_TRUE(names.insert(c.name).second) << c.name;
    EXPECT_FALSE(c.description.empty()) << c.name;
    EXPECT_NE(std::find(kStiffCaseCategories.begin(), kStiffCaseCategories.end(), c.category),
              kStiffCaseCategories.end())
        << c.name << ": unknown category " << c.category;
  }
  for (const char* category : kStiffCaseCategories)
    EXPECT_TRUE(categories.count(category)) << "category " << category << " has no case";
}

TEST(StiffCases, EveryCasePasses) {
  for (const StiffCase& c : stiffCases()) {
    CaseResult r = runStiffCase(c, options());
    EXPECT_TRUE(r.passed()) << c.name << ": expected " << r.expected << ", estimate " << r.estimate << " ± "
                            << r.standardError << ", z " << r.zScore() << ", bad " << r.bad
                            << (r.failures.empty() ? "" : ", " + r.failures.front()) << " [" << r.note << "]";
    EXPECT_EQ(r.bad, 0u) << c.name;
    EXPECT_TRUE(std::isfinite(r.estimate) && std::isfinite(r.standardError)) << c.name;
  }
}

// ---- the test of the test ------------------------------------------------------------------------

// Solid-angle light sampling with a pdf reported 2× too large (so each sample is weighted half).
struct HalvedSolidAngle {
  Color3 Li(const Scene& scene, const Ray& ray, Sampler& sampler) const {
    SurfaceHit hit;
    if (!scene.geometry.intersect(ray, hit)) return Color3(0.f);
    ShadingPoint sp(scene, ray, hit);
    const SphereLight& light = scene.sphereLights[0];
    LightSample s = light.sampleSolidAngle(hit.p, sampler.next2D());
    if (!(s.pdf > 0.f)) return Color3(0.f);
    float cosTheta = std::max(0.f, glm::dot(sp.ns, s.wi));
    return sp.material->bsdf.albedo * kInvPi * s.Le * (cosTheta / (2.f * s.pdf));
  }
};

TEST(StiffCasesCanFail, APdfOffByTwoFailsTheZTest) {
  LoadedScene s = loadScene(options().sceneDir + "/light-straddling.xml");
  const Vec3 x(0.31f, 0.17f, 0.f);
  const SphereLight& l = s.scene->sphereLights[0];
  double truth = l.radiance.x / kPiD *
                 sphereLightIrradianceFactor(glm::dvec3(x), glm::dvec3(0, 0, 1), glm::dvec3(l.sphere.center),
                                             l.sphere.radius);
  Estimate e = estimateRay(*s.scene, HalvedSolidAngle{}, shallowRayOnto(x), 4000, 3);
  CaseResult r;
  r.expected = truth;
  r.estimate = e.mean;
  r.standardError = e.standardError;
  r.bad = e.bad;
  EXPECT_FALSE(r.passed()) << "a pdf off by 2x passed: " << e.mean << " ± " << e.standardError << " vs "
                           << truth;
  EXPECT_GT(r.zScore(), 4.0);
  // The same estimate with the right expectation passes (the failure above is the pdf's).
  r.expected = truth / 2;
  EXPECT_TRUE(r.passed()) << r.zScore();
}

TEST(StiffCasesCanFail, AWrongExpectedValueANaNOrAFailedInvariantFails) {
  const StiffCase* cone = nullptr;
  for (const StiffCase& c : stiffCases())
    if (c.name == "light-straddling") cone = &c;
  ASSERT_NE(cone, nullptr);
  CaseResult good = runStiffCase(*cone, options());
  ASSERT_TRUE(good.passed());

  CaseResult wrong = good;
  wrong.expected = good.estimate + 6 * good.standardError;  // 6 SE away
  EXPECT_FALSE(wrong.passed());

  CaseResult nan = good;
  nan.bad = 1;  // one NaN/Inf/negative sample
  EXPECT_FALSE(nan.passed());

  CaseResult notFinite = good;
  notFinite.estimate = std::nan("");
  EXPECT_FALSE(notFinite.passed());

  CaseResult invariant = good;
  invariant.failures.push_back("deliberately broken");
  EXPECT_FALSE(invariant.passed());

  // Deterministic cases: the slack is tiny, so a value one part in 10^4 off fails.
  CaseResult exact;
  exact.expected = 1.0;
  exact.estimate = 1.0001;
  exact.relSlack = 0;
  exact.absSlack = 1e-6;
  EXPECT_FALSE(exact.passed());
  exact.estimate = 1.0000005;
  EXPECT_TRUE(exact.passed());
}

TEST(StiffCasesCanFail, AWrongRejectionMessageOrAnAcceptedFileFails) {
  EXPECT_TRUE(checkRejected(options(), "bad-nan.xml", "expected a finite number").passed());
  EXPECT_FALSE(checkRejected(options(), "bad-nan.xml", "sampleCount must be").passed());
  EXPECT_FALSE(checkRejected(options(), "light-straddling.xml", "anything").passed());  // accepted: fails
}

TEST(StiffCasesCanFail, AMissingSceneDirectoryFailsInsteadOfThrowing) {
  CaseOptions o;
  o.sceneDir = "/nonexistent/stiff";
  for (const StiffCase& c : stiffCases()) {
    if (c.name == "light-straddling" || c.name == "scale-ao") {
      EXPECT_FALSE(runStiffCase(c, o).passed()) << c.name;
    }
  }
}

}  // namespace
}  // namespace penumbra::analysis
