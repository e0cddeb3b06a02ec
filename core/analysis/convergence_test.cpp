#include "core/analysis/convergence.h"

#include <gtest/gtest.h>

#include "core/math/error.h"

namespace penumbra {
namespace {

std::vector<Strategy> strategiesOf(const std::vector<IntegratorDesc>& descs) {
  std::vector<Strategy> out;
  for (const IntegratorDesc& d : descs) out.push_back(d.strategy);
  return out;
}

TEST(ParseStrategies, AllIsEveryStrategyOfTheTypeInTableOrder) {
  IntegratorDesc direct{Strategy::DirectArea, 2};
  std::vector<IntegratorDesc> all = parseStrategies(direct, "all");
  EXPECT_EQ(strategiesOf(all), strategiesOfType("direct"));
  for (const IntegratorDesc& d : all) EXPECT_EQ(d.samples, 2);
  EXPECT_EQ(strategiesOf(parseStrategies(direct, "")), strategiesOfType("direct"));
  EXPECT_EQ(strategiesOf(parseStrategies({Strategy::AoCosine, 1}, "all")), strategiesOfType("ao"));
}

TEST(ParseStrategies, LabelsShortNamesAndSceneSpellingsNameTheirRow) {
  IntegratorDesc direct{Strategy::DirectSolidAngle, 1};
  EXPECT_EQ(strategiesOf(parseStrategies(direct, "direct/area,solidAngle,uniform,cosine-hemisphere")),
            (std::vector<Strategy>{Strategy::DirectArea, Strategy::DirectSolidAngle,
                                   Strategy::DirectUniformHemisphere, Strategy::DirectCosineHemisphere}));
  EXPECT_EQ(strategiesOf(parseStrategies({Strategy::AoUniform, 1}, "cosine,ao-uniform")),
            (std::vector<Strategy>{Strategy::AoCosine, Strategy::AoUniform}));
}

TEST(ParseStrategies, UnknownNamesFailWithWhatIsAccepted) {
  try {
    parseStrategies({Strategy::DirectSolidAngle, 1}, "area,mis");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(
        std::string(e.what()).find("unknown strategy \"mis\" (expected all, or a comma-separated list of: "
                                   "uniform-hemisphere, cosine-hemisphere, area, solid-angle)"),
        std::string::npos)
        << e.what();
  }
  EXPECT_THROW(parseStrategies({Strategy::Normals, 1}, "all"), Error);
  EXPECT_NE(strategyNamesHelp().find("ao: ao-uniform ao-cosine"), std::string::npos) << strategyNamesHelp();
}

}  // namespace
}  // namespace penumbra
