// strategy_choices: why a strategy cannot light a scene, and what compare mode's right side may
// render next to the left one.
#include "app/ui/strategy_choices.h"

#include <gtest/gtest.h>

#include "core/math/error.h"
#include "core/render/strategy_axes.h"

using namespace penumbra;
using namespace penumbra::ui;

TEST(StrategyChoices, CompareOffersTheLeftTypesStrategiesThatApply) {
  const IntegratorDesc left = directByLight(LightMeasure::SolidAngle);
  EXPECT_TRUE(offersCompare(left));
  EXPECT_TRUE(offersCompare(aoBy(HemisphereWarp::Cosine)));
  EXPECT_FALSE(offersCompare(integratorOfType(IntegratorType::Normals)));
  EXPECT_TRUE(comparable(directByMis(LightMeasure::Area, MisHeuristic::Power), left, true));
  EXPECT_FALSE(comparable(directByMis(LightMeasure::Area, MisHeuristic::Power), left, false));
  EXPECT_FALSE(comparable(aoBy(HemisphereWarp::Uniform), left, true));
  // The default right side differs from the left and applies: the first in axis-table order.
  EXPECT_EQ(strategyLabel(defaultCompareStrategy(left, true)), "direct/uniform-hemisphere");
  EXPECT_EQ(strategyLabel(defaultCompareStrategy(directByHemisphere(HemisphereWarp::Uniform), false)),
            "direct/cosine-hemisphere");
  EXPECT_EQ(strategyLabel(defaultCompareStrategy(aoBy(HemisphereWarp::Uniform), false)), "ao/cosine");
}

TEST(StrategyChoices, CompareNamesAMeasureWithTheLeftSidesOtherAxes) {
  const IntegratorDesc left = withSamples(directByLight(LightMeasure::SolidAngle, LightSelection::Bvh), 3);
  EXPECT_EQ(strategyLabel(parseCompareStrategy("area", left, true)), "direct/area-bvh");
  EXPECT_EQ(parseCompareStrategy("area", left, true).samples, 3);
  EXPECT_EQ(strategyLabel(parseCompareStrategy("mis", left, true)), "direct/mis/solid-angle/power");
  EXPECT_EQ(strategyLabel(parseCompareStrategy("area-power", left, true)), "direct/area-power");
  EXPECT_EQ(
      strategyLabel(parseCompareStrategy("uniform", withSamples(aoBy(HemisphereWarp::Cosine), 5), false)),
      "ao/uniform");
  try {
    parseCompareStrategy("area", left, false);  // needs area lights
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "--compare area: expected one direct strategy that applies to this scene: uniform-hemisphere, "
              "cosine-hemisphere, bsdf");
  }
  EXPECT_THROW(parseCompareStrategy("hemisphere", left, true), Error);  // two strategies
  EXPECT_THROW(parseCompareStrategy("nonsense", aoBy(HemisphereWarp::Cosine), false), Error);
  EXPECT_THROW(parseCompareStrategy("area", integratorOfType(IntegratorType::Normals), true), Error);
}

TEST(StrategyChoices, UnavailableReasons) {
  EXPECT_EQ(strategyUnavailableReason(aoBy(HemisphereWarp::Cosine), nullptr), "");
  EXPECT_EQ(strategyUnavailableReason(directByHemisphere(HemisphereWarp::Cosine), nullptr),
            "needs lights: the scene has none");
  EXPECT_EQ(strategyUnavailableReason(directByLight(LightMeasure::Area), nullptr),
            "needs area lights (renders direct/cosine-hemisphere here)");
  EXPECT_EQ(strategyUnavailableReason(integratorOfType(IntegratorType::Simple), nullptr),
            "needs point or directional lights");
  EXPECT_EQ(lightSelectionDefaultText(300), "default for 300 area lights: bvh (all up to 256)");
}
