// The scene builder's light selection when the scene names none: every light up to kAllLightsUpTo
// sphere lights, kManyLightsSelection above, for every measure that takes a light selection; a named
// selection always wins.
#include "core/scene/light_selection_default.h"

#include <gtest/gtest.h>

#include <string>

#include "core/render/strategy_axes.h"
#include "core/scene/scaling_scene.h"
#include "core/scene/scene_builder.h"
#include "core/scene/xml_parser.h"

namespace penumbra {
namespace {

// The scaling scene with n sphere lights (and n blockers), its integrator set by `sets`.
RenderSettings settingsFor(int lights, const std::vector<std::pair<std::string, std::string>>& sets) {
  SceneNode desc = parseSceneString(scalingSceneXml(lights, 16, 1), "scaling.xml", ".");
  for (const auto& [k, v] : sets) applyOverride(desc, k, v);
  EXPECT_EQ(countSphereLights(desc), size_t(lights));
  return buildSettings(desc);
}

// The figures that set the threshold (docs/estimators.md, "Many lights": the crossover table): `all` is at
// least as efficient as `bvh` through 256 lights with every light measure, `bvh` wins at 512.
TEST(LightSelectionDefault, FollowsTheMeasuredCrossover) {
  EXPECT_EQ(kAllLightsUpTo, 256u);
  EXPECT_EQ(kManyLightsSelection, LightSelection::Bvh);
  for (size_t n : {0, 1, 2, 8, 64, 128, 256}) EXPECT_EQ(defaultLightSelection(n), LightSelection::All) << n;
  for (size_t n : {257, 512, 1000, 10000}) EXPECT_EQ(defaultLightSelection(n), LightSelection::Bvh) << n;
}

TEST(LightSelectionDefault, AbsentResolvesByTheSceneLightCount) {
  const int at = int(kAllLightsUpTo), above = int(kAllLightsUpTo) + 1;
  // The scaling scene names measure solid-angle and no lightSelection.
  EXPECT_EQ(strategyLabel(settingsFor(1, {}).integrator),
            strategyLabel(directByLight(LightMeasure::SolidAngle)));
  EXPECT_EQ(strategyLabel(settingsFor(at, {}).integrator),
            strategyLabel(directByLight(LightMeasure::SolidAngle)));
  EXPECT_EQ(strategyLabel(settingsFor(above, {}).integrator),
            strategyLabel(directByLight(LightMeasure::SolidAngle, LightSelection::Bvh)));
  EXPECT_EQ(strategyLabel(settingsFor(64, {}).integrator),
            strategyLabel(directByLight(LightMeasure::SolidAngle)));
  // Area sampling resolves the same way; the hemisphere measures take no light selection.
  EXPECT_EQ(strategyLabel(settingsFor(at, {{"integrator.measure", "area"}}).integrator),
            strategyLabel(directByLight(LightMeasure::Area)));
  EXPECT_EQ(strategyLabel(settingsFor(above, {{"integrator.measure", "area"}}).integrator),
            strategyLabel(directByLight(LightMeasure::Area, LightSelection::Bvh)));
  EXPECT_EQ(strategyLabel(settingsFor(at, {{"integrator.measure", "projected-solid-angle"}}).integrator),
            strategyLabel(directByLight(LightMeasure::ProjectedSolidAngle)));
  EXPECT_EQ(strategyLabel(settingsFor(above, {{"integrator.measure", "projected-solid-angle"}}).integrator),
            strategyLabel(directByLight(LightMeasure::ProjectedSolidAngle, LightSelection::Bvh)));
  EXPECT_EQ(strategyLabel(settingsFor(above, {{"integrator.measure", "hemisphere"}}).integrator),
            strategyLabel(directByHemisphere(HemisphereWarp::Cosine)));
  // mis samples every light whatever the count: no light selection to resolve.
  EXPECT_EQ(strategyLabel(settingsFor(above, {{"integrator.measure", "mis"}}).integrator),
            strategyLabel(settingsFor(1, {{"integrator.measure", "mis"}}).integrator));
  EXPECT_FALSE(settingsFor(above, {{"integrator.measure", "mis"}}).integrator.usesLightSelection());
  // No <integrator> at all: the default strategy, resolved likewise.
  SceneNode bare = parseSceneString(scalingSceneXml(above, 16, 1), "scaling.xml", ".");
  std::erase_if(bare.children, [](const SceneNode& c) { return c.tag == "integrator"; });
  std::vector<std::string> warnings;
  EXPECT_EQ(strategyLabel(buildSettings(bare, &warnings).integrator),
            strategyLabel(directByLight(LightMeasure::SolidAngle, LightSelection::Bvh)));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("direct/solid-angle-bvh"), std::string::npos) << warnings[0];
}

TEST(LightSelectionDefault, ANamedSelectionAlwaysWins) {
  for (int n : {1, 64, int(kAllLightsUpTo) + 1})
    for (const char* measure : {"solid-angle", "area", "projected-solid-angle"})
      for (const char* name : {"all", "uniform", "power", "bvh"}) {
        RenderSettings s =
            settingsFor(n, {{"integrator.measure", measure}, {"integrator.lightSelection", name}});
        EXPECT_EQ(nameOf(s.integrator.lightSelection), name) << n << " " << measure;
        EXPECT_EQ(measureName(s.integrator), measure);
      }
}

// What `render` prints and writes into the image metadata.
TEST(LightSelectionDefault, SummarySaysWhetherTheSceneOrTheDefaultChose) {
  SceneNode many = parseSceneString(scalingSceneXml(300, 16, 1), "scaling.xml", ".");
  EXPECT_EQ(lightSelectionSummary(many, buildSettings(many).integrator, 300),
            "light selection bvh (the default for 300 area lights: all up to 256, bvh above)");
  SceneNode one = parseSceneString(scalingSceneXml(1, 16, 1), "scaling.xml", ".");
  EXPECT_EQ(lightSelectionSummary(one, buildSettings(one).integrator, 1),
            "light selection all (the default for 1 area light: all up to 256, bvh above)");
  applyOverride(many, "integrator.lightSelection", "power");
  EXPECT_EQ(lightSelectionSummary(many, buildSettings(many).integrator, 300),
            "light selection power (named by the scene or --set)");
  EXPECT_EQ(lightSelectionSummary(many, directByHemisphere(HemisphereWarp::Cosine), 300), "");
}

}  // namespace
}  // namespace penumbra
