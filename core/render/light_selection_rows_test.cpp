// The light-selection queries over the strategy table: every light-sampling measure offers all four
// selections as rows that differ from each other only in lightSelection.
#include "core/render/light_selection_rows.h"

#include <gtest/gtest.h>

#include <set>

#include "core/render/strategy_table.h"

namespace penumbra {
namespace {

TEST(LightSelectionRows, EveryMeasureOffersEachSelectionOnceAndSwitchesBack) {
  const std::vector<LightSelection> all = {LightSelection::All, LightSelection::Uniform,
                                           LightSelection::Power, LightSelection::Bvh};
  int measures = 0;
  for (const StrategyRow& row : strategyTable()) {
    const Strategy s = row.strategy;
    if (!takesLightSelection(s)) {
      EXPECT_TRUE(lightSelectionsOf(s).empty()) << row.label;
      EXPECT_EQ(allLightsRow(s), s) << row.label;
      EXPECT_FALSE(withLightSelection(s, LightSelection::Bvh).has_value()) << row.label;
      EXPECT_EQ(lightSelectionOf(s), LightSelection::All) << row.label;
      continue;
    }
    EXPECT_EQ(lightSelectionsOf(s), all) << row.label;
    const Strategy base = allLightsRow(s);
    if (base == s) ++measures;
    for (LightSelection l : all) {
      std::optional<Strategy> t = withLightSelection(s, l);
      ASSERT_TRUE(t.has_value()) << row.label;
      EXPECT_EQ(lightSelectionOf(*t), l) << row.label;
      // Same measure, same integrator: only the selection changed.
      EXPECT_EQ(samplesLightArea(*t), samplesLightArea(s)) << row.label;
      EXPECT_EQ(samplesLightSolidAngle(*t), samplesLightSolidAngle(s)) << row.label;
      EXPECT_EQ(samplesLightProjectedSolidAngle(*t), samplesLightProjectedSolidAngle(s)) << row.label;
      EXPECT_EQ(allLightsRow(*t), base) << row.label;
      EXPECT_EQ(withLightSelection(*t, lightSelectionOf(s)), s) << row.label;
    }
  }
  EXPECT_EQ(measures, 3);  // area, solid angle, projected solid angle (not mis: it samples every light)
}

TEST(LightSelectionRows, NamesAreTheXmlValues) {
  EXPECT_EQ(lightSelectionProperty().canonical(), "lightSelection");
  EXPECT_EQ(lightSelectionName(LightSelection::All), "all");
  EXPECT_EQ(lightSelectionName(LightSelection::Uniform), "uniform");
  EXPECT_EQ(lightSelectionName(LightSelection::Power), "power");
  EXPECT_EQ(lightSelectionName(LightSelection::Bvh), "bvh");
}

}  // namespace
}  // namespace penumbra
