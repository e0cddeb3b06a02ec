#include "core/render/strategy_axes.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "core/integrators/integrator_test_support.h"
#include "core/render/strategy_dispatch.h"

namespace penumbra {
namespace {

// No spelling names two values of one axis, and each value has a row with a description.
template <class Row, size_t N>
void expectUnambiguous(const std::array<Row, N>& table, Spellings Row::*spellings, const char* axis) {
  std::set<std::string_view> seen;
  for (const Row& r : table) {
    EXPECT_FALSE(r.description.empty()) << axis;
    for (std::string_view s : (r.*spellings).list()) EXPECT_TRUE(seen.insert(s).second) << axis << ": " << s;
  }
}

TEST(StrategyAxes, EverySpellingNamesOneValue) {
  expectUnambiguous(kIntegratorTypes, &IntegratorTypeRow::xmlType, "integrator");
  expectUnambiguous(kWarps, &WarpRow::spellings, "warp");
  expectUnambiguous(kLightMeasures, &LightMeasureRow::spellings, "light measure");
  expectUnambiguous(kLightSelections, &LightSelectionRow::spellings, "light selection");
  expectUnambiguous(kHeuristics, &HeuristicRow::spellings, "heuristic");
  // measure: hemisphere and mis beside the light measures, none spelled like another.
  std::set<std::string_view> measures;
  for (std::string_view m : measureNames()) EXPECT_TRUE(measures.insert(m).second) << m;
  EXPECT_EQ(acceptedMeasures(),
            "hemisphere, bsdf, area, solid-angle, solidAngle, projected-solid-angle, "
            "projectedSolidAngle, mis");
  for (const LightMeasureRow& m : kLightMeasures) {
    IntegratorDesc d;
    ASSERT_TRUE(applyMeasure(m.spellings.canonical(), d));
    EXPECT_EQ(d.estimator, Estimator::Light);
    EXPECT_EQ(d.lightMeasure, m.measure);
    EXPECT_EQ(measureName(d), m.spellings.canonical());
  }
  IntegratorDesc d;
  EXPECT_FALSE(applyMeasure("nonsense", d));
  EXPECT_EQ(acceptedIntegratorTypes(), "direct, ao, simple, normals");
}

TEST(StrategyAxes, LabelsAndShortNamesAreComposedAndUnique) {
  std::set<std::string> labels, shortNames;
  for (const IntegratorDesc& d : everyStrategy()) {
    const std::string label = strategyLabel(d);
    EXPECT_TRUE(labels.insert(label).second) << label;
    EXPECT_TRUE(shortNames.insert(strategyShortName(d)).second) << strategyShortName(d);
    EXPECT_EQ(label.substr(0, nameOf(d.type).size()), nameOf(d.type)) << label;
  }
  // direct's hemisphere warps, bsdf, light measures x selections and x heuristics; ao's warps; simple,
  // normals.
  const size_t direct =
      kWarps.size() + 1 + kLightMeasures.size() * (kLightSelections.size() + kHeuristics.size());
  EXPECT_EQ(labels.size(), direct + kWarps.size() + 2);
  EXPECT_EQ(strategyLabel(directByLight(LightMeasure::SolidAngle, LightSelection::Bvh)),
            "direct/solid-angle-bvh");
  EXPECT_EQ(strategyShortName(directByMis(LightMeasure::Area, MisHeuristic::Balance)), "mis-area-balance");
  EXPECT_EQ(strategyLabel(directByMis(LightMeasure::ProjectedSolidAngle, MisHeuristic::Power)),
            "direct/mis/projected-solid-angle/power");
  EXPECT_EQ(strategyLabel(directByHemisphere(HemisphereWarp::Uniform)), "direct/uniform-hemisphere");
  EXPECT_EQ(strategyLabel(aoBy(HemisphereWarp::Cosine)), "ao/cosine");
  EXPECT_EQ(strategyShortName(aoBy(HemisphereWarp::Uniform)), "ao-uniform");
  EXPECT_EQ(strategyLabel(integratorOfType(IntegratorType::Normals)), "normals");
}

// An axis that does not apply neither renders nor compares: the viewer keeps it for when the user
// returns to a measure that reads it.
TEST(StrategyAxes, AxesThatDoNotApplyDoNotCompare) {
  IntegratorDesc a = directByHemisphere(HemisphereWarp::Cosine), b = a;
  b.lightSelection = LightSelection::Bvh;
  b.heuristic = MisHeuristic::Balance;
  b.lightMeasure = LightMeasure::Area;
  EXPECT_EQ(a, b);
  EXPECT_EQ(strategyLabel(a), strategyLabel(b));
  b.warp = HemisphereWarp::Uniform;
  EXPECT_NE(a, b);
  IntegratorDesc light = directByLight(LightMeasure::Area), other = light;
  other.warp = HemisphereWarp::Uniform;
  EXPECT_EQ(light, other);
  other.lightSelection = LightSelection::Power;
  EXPECT_NE(light, other);
  EXPECT_NE(light, withSamples(light, 2));
  IntegratorDesc mis = directByMis(LightMeasure::Area, MisHeuristic::Power), misOther = mis;
  misOther.lightSelection = LightSelection::Bvh;
  EXPECT_EQ(mis, misOther);
  misOther.bsdfSamples = 3;
  EXPECT_NE(mis, misOther);
  EXPECT_EQ(integratorOfType(IntegratorType::Normals),
            withSamples(integratorOfType(IntegratorType::Normals), 9));
}

TEST(StrategyAxes, FallbacksApplyEverywhere) {
  for (const IntegratorDesc& d : everyStrategy()) {
    EXPECT_TRUE(strategyApplies(d, true)) << strategyLabel(d);
    const IntegratorDesc fallback = applicableStrategy(d, false);
    EXPECT_TRUE(strategyApplies(fallback, false)) << strategyLabel(d);
    EXPECT_EQ(fallback.type, d.type) << strategyLabel(d);
    EXPECT_EQ(applicableStrategy(d, true), d) << strategyLabel(d);
    if (sceneNeed(d) == SceneNeed::Nothing) {
      EXPECT_EQ(fallback, d) << strategyLabel(d);
    }
  }
  // Light sampling needs area lights; without them the scene renders by hemisphere sampling.
  EXPECT_EQ(applicableStrategy(directByLight(LightMeasure::Area), false),
            directByHemisphere(HemisphereWarp::Cosine));
  EXPECT_EQ(applicableStrategy(directByMis(LightMeasure::Area, MisHeuristic::Power), false),
            directByHemisphere(HemisphereWarp::Cosine));
  EXPECT_EQ(applicableStrategy(directByHemisphere(HemisphereWarp::Uniform), false),
            directByHemisphere(HemisphereWarp::Uniform));
  EXPECT_EQ(applicableStrategy(aoBy(HemisphereWarp::Uniform), false), aoBy(HemisphereWarp::Uniform));
}

TEST(StrategyAxes, ReferenceAndBaselineKeepTheCounts) {
  EXPECT_EQ(referenceStrategy(withSamples(directByLight(LightMeasure::Area, LightSelection::Bvh), 3)),
            withSamples(directByLight(LightMeasure::SolidAngle), 3));
  EXPECT_EQ(referenceStrategy(withSamples(directByLight(LightMeasure::Area), 3), true),
            withSamples(directByMis(LightMeasure::SolidAngle, MisHeuristic::Power), 3));
  EXPECT_EQ(referenceStrategy(aoBy(HemisphereWarp::Uniform)), aoBy(HemisphereWarp::Cosine));
  EXPECT_EQ(referenceStrategy(aoBy(HemisphereWarp::Uniform), true), aoBy(HemisphereWarp::Cosine));
  EXPECT_EQ(baselineStrategy(directByLight(LightMeasure::SolidAngle)),
            directByHemisphere(HemisphereWarp::Uniform));
  EXPECT_EQ(referenceStrategy(integratorOfType(IntegratorType::Normals)),
            integratorOfType(IntegratorType::Normals));
  int baselines = 0;
  for (const IntegratorDesc& d : everyStrategy()) baselines += isBaseline(d);
  EXPECT_EQ(baselines, 2);  // direct/uniform-hemisphere, ao/uniform
}

TEST(StrategyAxes, EveryStrategyOfTypeCrossesTheAxesThatApply) {
  const std::vector<IntegratorDesc> direct =
      everyStrategyOfType(withSamples(integratorOfType(IntegratorType::Direct), 5));
  ASSERT_EQ(direct.size(),
            kWarps.size() + 1 + kLightMeasures.size() * (kLightSelections.size() + kHeuristics.size()));
  EXPECT_EQ(strategyLabel(direct.front()), "direct/uniform-hemisphere");
  EXPECT_EQ(strategyLabel(direct[2]), "direct/bsdf");
  EXPECT_EQ(strategyLabel(direct[3]), "direct/area");
  EXPECT_EQ(strategyLabel(direct[4]), "direct/area-uniform");
  for (const IntegratorDesc& d : direct) EXPECT_EQ(d.samples, 5);
  EXPECT_EQ(everyStrategyOfType(aoBy(HemisphereWarp::Cosine)).size(), 2u);
  EXPECT_EQ(everyStrategyOfType(integratorOfType(IntegratorType::Simple)).size(), 1u);
}

TEST(StrategyAxes, CanonicalPropertiesUseTheFirstSpelling) {
  std::vector<CanonicalProperty> p = canonicalProperties(withSamples(aoBy(HemisphereWarp::Uniform), 3));
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].name, "shadingSamples");
  EXPECT_EQ(p[0].value, "3");
  EXPECT_TRUE(p[0].isInteger);
  EXPECT_EQ(p[1].name, "warp-type");
  EXPECT_EQ(p[1].value, "uniform-hemisphere");
  std::vector<CanonicalProperty> h =
      canonicalProperties(withSamples(directByHemisphere(HemisphereWarp::Cosine), 2));
  ASSERT_EQ(h.size(), 3u);
  EXPECT_EQ(h[1].name, "measure");
  EXPECT_EQ(h[1].value, "hemisphere");
  EXPECT_EQ(h[2].value, "cosine-hemisphere");
  std::vector<CanonicalProperty> m =
      canonicalProperties(directByMis(LightMeasure::Area, MisHeuristic::Balance));
  ASSERT_EQ(m.size(), 6u);
  EXPECT_EQ(m[1].name, "lightSamples");
  EXPECT_EQ(m[3].value, "mis");
  EXPECT_EQ(m[4].name, "lightMeasure");
  EXPECT_EQ(m[4].value, "area");
  EXPECT_EQ(m[5].value, "balance");
  std::vector<CanonicalProperty> l =
      canonicalProperties(directByLight(LightMeasure::SolidAngle, LightSelection::Bvh));
  ASSERT_EQ(l.size(), 3u);
  EXPECT_EQ(l[2].name, "lightSelection");
  EXPECT_EQ(l[2].value, "bvh");
  EXPECT_TRUE(canonicalProperties(withSamples(integratorOfType(IntegratorType::Normals), 1)).empty());
  EXPECT_TRUE(integratorReads(directByLight(LightMeasure::Area), "light-selection"));
  EXPECT_FALSE(integratorReads(directByLight(LightMeasure::Area), "heuristic"));
  EXPECT_TRUE(integratorReads(directByMis(LightMeasure::Area, MisHeuristic::Power), "bsdfSamples"));
}

// Each strategy's estimator instantiates its own integrator: at the origin of the plane under one
// sphere light (fully above the horizon: E/π = L sin²α cos θ; AO = 1 − sin²α cos θ, the light being
// the only occluder), every strategy estimates its own quantity.
TEST(StrategyAxes, EachStrategyEstimatesWithItsOwnIntegrator) {
  const Vec3 c(0.6f, 0.f, 2.f);
  const float r = 0.5f, L = 3.f;
  auto scene = test::planeScene();
  test::addSphere(*scene, c, r, Color3(L));
  test::finish(*scene);
  const double d2 = double(c.x) * c.x + double(c.z) * c.z;
  const double projected = (double(r) * r / d2) * (c.z / std::sqrt(d2));  // sin²α cos θ
  for (const IntegratorDesc& d : everyStrategy()) {
    const bool hemisphere = sceneNeed(d) == SceneNeed::Nothing;
    RayEstimate e = estimateRayOf(d, *scene, test::rayDownOnto(0.f, 0.f), hemisphere ? 100000 : 20000, 9);
    const double truth = d.type == IntegratorType::Direct ? L * projected
                         : d.type == IntegratorType::Ao   ? 1.0 - projected
                                                          : 0.0;
    EXPECT_EQ(e.bad, 0u) << strategyLabel(d);
    EXPECT_NEAR(e.mean, truth, 4.0 * e.standardError + 1e-6) << strategyLabel(d) << " ± " << e.standardError;
  }
}

}  // namespace
}  // namespace penumbra
