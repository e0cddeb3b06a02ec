#include "core/analysis/strategy_lists.h"

#include <gtest/gtest.h>

#include "core/math/error.h"
#include "core/render/strategy_axes.h"

namespace penumbra {
namespace {

std::vector<std::string> labelsOf(const std::vector<IntegratorDesc>& descs) {
  std::vector<std::string> out;
  for (const IntegratorDesc& d : descs) out.push_back(strategyLabel(d));
  return out;
}

std::vector<std::string> parsed(const IntegratorDesc& base, StrategyLists lists) {
  return labelsOf(parseStrategyLists(base, lists).strategies);
}

const IntegratorDesc kDirect = directByLight(LightMeasure::SolidAngle);

TEST(StrategyLists, AllIsEveryMeasureWithTheScenesAxes) {
  const IntegratorDesc base = withSamples(directByLight(LightMeasure::Area, LightSelection::Power), 2);
  const std::vector<IntegratorDesc> all = parseStrategies(base, "all");
  EXPECT_EQ(labelsOf(all),
            (std::vector<std::string>{"direct/uniform-hemisphere", "direct/cosine-hemisphere", "direct/bsdf",
                                      "direct/area-power", "direct/solid-angle-power",
                                      "direct/projected-solid-angle-power", "direct/mis/solid-angle/power"}));
  for (const IntegratorDesc& d : all) EXPECT_EQ(d.samples, 2);
  EXPECT_EQ(labelsOf(parseStrategies(base, "")), labelsOf(all));
  EXPECT_EQ(labelsOf(parseStrategies(aoBy(HemisphereWarp::Cosine), "all")),
            (std::vector<std::string>{"ao/uniform", "ao/cosine"}));
  // A mis scene's own light measure and heuristic are the defaults of the mis runs.
  EXPECT_EQ(labelsOf(parseStrategies(directByMis(LightMeasure::Area, MisHeuristic::Balance), "mis")),
            (std::vector<std::string>{"direct/mis/area/balance"}));
}

TEST(StrategyLists, EachAxisListCrossesTheMeasuresItAppliesTo) {
  EXPECT_EQ(parsed(kDirect, {"area,mis,cosine-hemisphere", "all,bvh", "area,solid-angle", "power,balance"}),
            (std::vector<std::string>{"direct/area", "direct/area-bvh", "direct/mis/area/power",
                                      "direct/mis/area/balance", "direct/mis/solid-angle/power",
                                      "direct/mis/solid-angle/balance", "direct/cosine-hemisphere"}));
  // "hemisphere" is both warps; each strategy once, in the order first named.
  EXPECT_EQ(parsed(kDirect, {"hemisphere,uniform-hemisphere,solidAngle", "", "", ""}),
            (std::vector<std::string>{"direct/uniform-hemisphere", "direct/cosine-hemisphere",
                                      "direct/solid-angle"}));
  EXPECT_EQ(parsed(aoBy(HemisphereWarp::Uniform), {"cosine,ao-uniform", "bvh", "", ""}),
            (std::vector<std::string>{"ao/cosine", "ao/uniform"}));  // no light selection in ao
}

TEST(StrategyLists, OldFlattenedNamesStillWorkWithANotice) {
  const ParsedStrategies p =
      parseStrategyLists(kDirect, {"solid-angle-bvh,direct/mis/area/balance,area", "", "", ""});
  EXPECT_EQ(labelsOf(p.strategies),
            (std::vector<std::string>{"direct/solid-angle-bvh", "direct/mis/area/balance", "direct/area"}));
  ASSERT_EQ(p.notices.size(), 2u);
  EXPECT_EQ(p.notices[0],
            "converge: \"solid-angle-bvh\" is an old name; write --strategies solid-angle "
            "--light-selection bvh");
  EXPECT_EQ(p.notices[1],
            "converge: \"direct/mis/area/balance\" is an old name; write --strategies mis "
            "--light-measure area --heuristic balance");
  EXPECT_TRUE(parseStrategyLists(kDirect, {"area,mis", "", "", ""}).notices.empty());
}

TEST(StrategyLists, UnknownNamesFailWithWhatIsAccepted) {
  try {
    parseStrategies(kDirect, "area,bogus");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "unknown strategy \"bogus\" (expected all, or a comma-separated list of: "
              "uniform-hemisphere, cosine-hemisphere, bsdf, area, solid-angle, "
              "projected-solid-angle, mis)");
  }
  // Values of another axis are not measures.
  EXPECT_THROW(parseStrategies(kDirect, "power"), Error);
  EXPECT_THROW(parseStrategies(kDirect, "bvh"), Error);
  EXPECT_THROW(parseStrategies(aoBy(HemisphereWarp::Cosine), "solid-angle"), Error);
  try {
    parseStrategyLists(kDirect, {"area", "nearest", "", ""});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "unknown light selection \"nearest\" (expected some of: all, uniform, power, bvh)");
  }
  EXPECT_THROW(parseStrategyLists(kDirect, {"mis", "", "", "greedy"}), Error);
  EXPECT_THROW(parseStrategyLists(kDirect, {"mis", "", "hemisphere", ""}), Error);
  EXPECT_THROW(parseStrategies(integratorOfType(IntegratorType::Normals), "all"), Error);
  EXPECT_EQ(strategyNamesHelp(),
            "direct: uniform-hemisphere, cosine-hemisphere, bsdf, area, solid-angle, "
            "projected-solid-angle, mis; ao: uniform-hemisphere, cosine-hemisphere");
}

}  // namespace
}  // namespace penumbra
