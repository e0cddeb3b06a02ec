#include "core/render/strategy_table.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "core/integrators/integrator_test_support.h"
#include "core/render/row_renderer.h"

namespace penumbra {
namespace {

TEST(StrategyTable, RowsAreInEnumOrderAndComplete) {
  ASSERT_EQ(strategyTable().size(), size_t(kStrategyCount));
  for (size_t i = 0; i < strategyTable().size(); ++i) {
    const StrategyRow& r = strategyTable()[i];
    EXPECT_EQ(size_t(r.strategy), i) << r.label;
    EXPECT_NE(r.makeRows, nullptr) << r.label;
    EXPECT_NE(r.estimateRay, nullptr) << r.label;
    EXPECT_FALSE(r.description.empty()) << r.label;
    EXPECT_FALSE(r.xmlType.empty()) << r.label;
  }
}

TEST(StrategyTable, LabelsAndShortNamesAreUnique) {
  std::set<std::string_view> labels, shortNames;
  for (const StrategyRow& r : strategyTable()) {
    EXPECT_TRUE(labels.insert(r.label).second) << r.label;
    EXPECT_TRUE(shortNames.insert(r.shortName).second) << r.shortName;
    // A label names its integrator type first: "direct/area", or just "normals".
    EXPECT_EQ(r.label.substr(0, r.xmlType.size()), r.xmlType) << r.label;
  }
}

// What the scene builder relies on: within one integrator type every row spells the shading samples
// and each selecting property alike, and the selecting values tell the rows apart, with exactly one
// default wherever a property may be left out.
TEST(StrategyTable, RowsOfOneTypeAreSelectedUnambiguously) {
  // Rows that agree on the selecting values before `level` share that level's property name.
  auto samePrefix = [](const StrategyRow& a, const StrategyRow& b, size_t level) {
    for (size_t i = 0; i < level; ++i)
      if (a.select[i].value.names != b.select[i].value.names) return false;
    return true;
  };
  for (const StrategyRow& a : strategyTable()) {
    for (const StrategyRow& b : strategyTable()) {
      if (a.xmlType != b.xmlType) continue;
      EXPECT_EQ(a.samplesProperty.names, b.samplesProperty.names) << a.label << " vs " << b.label;
      for (size_t level = 0; level < kMaxSelectors; ++level) {
        if (!samePrefix(a, b, level)) break;
        EXPECT_EQ(a.select[level].name.names, b.select[level].name.names)
            << a.label << " vs " << b.label << ", level " << level;
        // No spelling of one row's value may select another row at the first level they differ.
        if (a.select[level].value.names != b.select[level].value.names) {
          for (std::string_view v : a.select[level].value.list()) {
            EXPECT_FALSE(b.select[level].value.accepts(v)) << v;
          }
        }
      }
      if (&a != &b) {
        EXPECT_FALSE(samePrefix(a, b, kMaxSelectors))
            << a.label << " and " << b.label << " are selected by the same values";
      }
    }
    // One default among the rows that share each level's context.
    for (size_t level = 0; level < kMaxSelectors; ++level) {
      if (a.select[level].name.empty()) continue;
      // Several rows may carry the default value (mis: solid-angle with either heuristic); one value is.
      std::set<std::vector<std::string_view>> defaults;
      for (const StrategyRow& b : strategyTable())
        if (b.xmlType == a.xmlType && samePrefix(a, b, level) && b.select[level].isDefault)
          defaults.insert(std::vector<std::string_view>(b.select[level].value.list().begin(),
                                                        b.select[level].value.list().end()));
      EXPECT_EQ(defaults.size(), 1u) << a.label << ", level " << level;
    }
  }
}

TEST(StrategyTable, FallbacksApplyEverywhere) {
  for (const StrategyRow& r : strategyTable()) {
    EXPECT_TRUE(strategyApplies(r.strategy, true)) << r.label;
    EXPECT_TRUE(strategyApplies(r.fallback, false)) << r.label;
    EXPECT_TRUE(sameIntegratorType(r.strategy, r.fallback)) << r.label;
    EXPECT_EQ(applicableStrategy(r.strategy, true), r.strategy) << r.label;
    if (r.needs == SceneNeed::Nothing) {
      EXPECT_EQ(r.fallback, r.strategy) << r.label;
    }
  }
  // Light sampling needs area lights; without them the scene renders by hemisphere sampling.
  EXPECT_EQ(applicableStrategy(Strategy::DirectArea, false), Strategy::DirectCosineHemisphere);
  EXPECT_EQ(applicableStrategy(Strategy::DirectSolidAngle, false), Strategy::DirectCosineHemisphere);
  EXPECT_EQ(applicableStrategy(Strategy::DirectUniformHemisphere, false), Strategy::DirectUniformHemisphere);
  EXPECT_EQ(applicableStrategy(Strategy::AoUniform, false), Strategy::AoUniform);
}

TEST(StrategyTable, EachTypeHasAtMostOneReferenceAndOneBaseline) {
  for (const StrategyRow& r : strategyTable()) {
    int references = 0, baselines = 0;
    for (Strategy s : strategiesOfType(r.xmlType)) {
      references += strategyRow(s).reference;
      baselines += strategyRow(s).baseline;
    }
    EXPECT_LE(references, 1) << r.xmlType;
    EXPECT_LE(baselines, 1) << r.xmlType;
    EXPECT_TRUE(sameIntegratorType(referenceStrategy(r.strategy), r.strategy));
  }
  EXPECT_EQ(referenceStrategy(Strategy::DirectArea), Strategy::DirectSolidAngle);
  EXPECT_EQ(referenceStrategy(Strategy::AoUniform), Strategy::AoCosine);
  EXPECT_EQ(baselineStrategy(Strategy::DirectSolidAngle), Strategy::DirectUniformHemisphere);
  EXPECT_EQ(referenceStrategy(Strategy::Normals), Strategy::Normals);
}

TEST(StrategyTable, CanonicalPropertiesUseTheFirstSpelling) {
  IntegratorDesc ao{Strategy::AoUniform, 3};
  std::vector<CanonicalProperty> p = canonicalProperties(ao);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].name, "shadingSamples");
  EXPECT_EQ(p[0].value, "3");
  EXPECT_TRUE(p[0].isInteger);
  EXPECT_EQ(p[1].name, "warp-type");
  EXPECT_EQ(p[1].value, "uniform-hemisphere");
  std::vector<CanonicalProperty> h = canonicalProperties({Strategy::DirectCosineHemisphere, 2});
  ASSERT_EQ(h.size(), 3u);
  EXPECT_EQ(h[1].name, "measure");
  EXPECT_EQ(h[1].value, "hemisphere");
  EXPECT_EQ(h[2].value, "cosine-hemisphere");
  EXPECT_TRUE(canonicalProperties({Strategy::Normals, 1}).empty());
  EXPECT_EQ(acceptedIntegratorTypes(), "direct, ao, simple, normals");
}

// Each row's estimator instantiates its own integrator: at the origin of the plane under one sphere
// light (fully above the horizon: E/π = L sin²α cos θ; AO = 1 − sin²α cos θ, the light being the
// only occluder), every row estimates its own quantity.
TEST(StrategyTable, EachRowEstimatesWithItsOwnIntegrator) {
  const Vec3 c(0.6f, 0.f, 2.f);
  const float r = 0.5f, L = 3.f;
  auto scene = test::planeScene();
  test::addSphere(*scene, c, r, Color3(L));
  test::finish(*scene);
  const double d2 = double(c.x) * c.x + double(c.z) * c.z;
  const double projected = (double(r) * r / d2) * (c.z / std::sqrt(d2));  // sin²α cos θ
  for (const StrategyRow& row : strategyTable()) {
    bool hemisphere = row.needs == SceneNeed::Nothing;
    RayEstimate e = row.estimateRay(*scene, test::rayDownOnto(0.f, 0.f), 1, hemisphere ? 100000 : 20000, 9,
                                    SamplerKind::Independent);
    double truth = row.xmlType == "direct" ? L * projected : row.xmlType == "ao" ? 1.0 - projected : 0.0;
    EXPECT_EQ(e.bad, 0u) << row.label;
    EXPECT_NEAR(e.mean, truth, 4.0 * e.standardError + 1e-6) << row.label << " ± " << e.standardError;
  }
}

}  // namespace
}  // namespace penumbra
