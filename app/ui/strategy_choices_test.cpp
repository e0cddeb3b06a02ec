// strategy_choices: the list shows each light-sampling measure once, a choice keeps the live light
// selection, and compare mode offers the strategies of the left side's type that apply.
#include "app/ui/strategy_choices.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/math/error.h"
#include "core/render/light_selection_rows.h"
#include "core/render/strategy_table.h"

using namespace penumbra;
using namespace penumbra::ui;

TEST(StrategyChoices, EachMeasureOnceAndAChoiceKeepsTheSelection) {
  const std::vector<Strategy> list = strategyChoices();
  for (Strategy s : list) EXPECT_EQ(lightSelectionOf(s), LightSelection::All) << strategyRow(s).label;
  EXPECT_NE(std::find(list.begin(), list.end(), Strategy::DirectArea), list.end());
  EXPECT_EQ(std::find(list.begin(), list.end(), Strategy::DirectAreaPower), list.end());
  EXPECT_EQ(strategyForChoice(Strategy::DirectArea, Strategy::DirectSolidAnglePower, LightSelection::All),
            Strategy::DirectAreaPower);
  EXPECT_EQ(strategyForChoice(Strategy::DirectArea, Strategy::AoCosine, LightSelection::Bvh),
            Strategy::DirectAreaBvh);
  EXPECT_EQ(strategyForChoice(Strategy::AoCosine, Strategy::DirectAreaPower, LightSelection::All),
            Strategy::AoCosine);
}

TEST(StrategyChoices, CompareOffersTheLeftTypesStrategiesThatApply) {
  for (Strategy s : compareChoices(Strategy::DirectSolidAngle, true))
    EXPECT_TRUE(sameIntegratorType(s, Strategy::DirectSolidAngle)) << strategyRow(s).label;
  const std::vector<Strategy> dark = compareChoices(Strategy::DirectSolidAngle, false);
  for (Strategy s : dark) EXPECT_TRUE(strategyApplies(s, false)) << strategyRow(s).label;
  EXPECT_EQ(parseCompareStrategy("ao/uniform", IntegratorDesc{Strategy::AoCosine, 5}, false).samples, 5);
  EXPECT_THROW(parseCompareStrategy("nonsense", IntegratorDesc{Strategy::AoCosine, 1}, false), Error);
  EXPECT_EQ(strategyUnavailableReason(Strategy::AoCosine, nullptr), "");
  EXPECT_EQ(strategyUnavailableReason(Strategy::DirectCosineHemisphere, nullptr),
            "needs lights: the scene has none");
}
