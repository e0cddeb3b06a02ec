#include "core/scene/scene_builder.h"

#include <gtest/gtest.h>

#include "core/math/error.h"

namespace penumbra {
namespace {

LoadedScene fromXml(const std::string& body) {
  return loadSceneFromString("<scene>\n" + body + "\n</scene>", "t.xml", ".");
}

// Expects loading to fail with a message containing file:line and `needle`.
void expectError(const std::string& body, int line, const std::string& needle) {
  try {
    fromXml(body);
    FAIL() << "no error for: " << body;
  } catch (const Error& e) {
    std::string what = e.what();
    EXPECT_NE(what.find("t.xml:" + std::to_string(line)), std::string::npos) << what;
    EXPECT_NE(what.find(needle), std::string::npos) << what;
  }
}

TEST(SceneBuilder, SeedSpellingsOfTheIntegrators) {
  auto ao = fromXml(R"(<integrator type="ao"><integer name="shadingSamples" value="4"/>
                       <string name="sampler" value="uniform"/></integrator>)");
  EXPECT_EQ(ao.settings.integrator.strategy, Strategy::AoUniform);
  EXPECT_EQ(ao.settings.integrator.samples, 4);
  auto ao2 = fromXml(R"(<integrator type="ao"><integer name="nSamples" value="2"/>
                        <string name="warp-type" value="cosine-hemisphere"/></integrator>)");
  EXPECT_EQ(ao2.settings.integrator.samples, 2);
  EXPECT_EQ(ao2.settings.integrator.strategy, Strategy::AoCosine);
  auto d = fromXml(R"(<integrator type="direct"><integer name="nSamples" value="3"/>
                      <string name="measure" value="solidAngle"/></integrator>)");
  EXPECT_EQ(d.settings.integrator.strategy, Strategy::DirectSolidAngle);
  auto h = fromXml(R"(<integrator type="direct"><string name="measure" value="hemisphere"/>
                      <string name="warp-type" value="uniform-hemisphere"/></integrator>)");
  EXPECT_EQ(h.settings.integrator.strategy, Strategy::DirectUniformHemisphere);
}

TEST(SceneBuilder, BadCountsAreRejectedWithTheirLine) {
  for (const char* v : {"0", "-4", "4294967296"})
    expectError(std::string("<sampler type=\"independent\">\n<integer name=\"sampleCount\" value=\"") + v +
                    "\"/></sampler>",
                3, "sampleCount");
  expectError("<sampler type=\"independent\">\n<integer name=\"sampleCount\" value=\"3.5\"/></sampler>", 3,
              "integer");
  expectError("<integrator type=\"ao\">\n<integer name=\"shadingSamples\" value=\"0\"/></integrator>", 3,
              "shadingSamples");
}

TEST(SceneBuilder, BadValuesAreRejectedWithTheirLine) {
  expectError("<shape type=\"sphere\">\n<float name=\"radius\" value=\"-1\"/></shape>", 3, "radius");
  expectError("<shape type=\"sphere\">\n<float name=\"radius\" value=\"nan\"/></shape>", 3, "");
  expectError("<shape type=\"sphere\">\n<float name=\"radius\" value=\"1e999\"/></shape>", 3, "");
  expectError("<shape type=\"sphere\">\n<point name=\"center\" value=\"inf,0,0\"/></shape>", 3, "");
  expectError("<camera type=\"perspective\">\n<float name=\"fov\" value=\"180\"/></camera>", 3, "fov");
  expectError("<camera type=\"perspective\">\n<float name=\"fov\" value=\"0\"/></camera>", 3, "fov");
  expectError("\n<integrator type=\"path\"/>", 3, "unknown integrator type \"path\"");
  expectError("<integrator type=\"direct\">\n<string name=\"measure\" value=\"volume\"/></integrator>", 3,
              "measure");
  expectError("\n<shape type=\"obj\"><string name=\"filename\" value=\"missing.obj\"/></shape>", 3,
              "cannot open mesh file 'missing.obj'");
  expectError(
      "<shape type=\"sphere\">\n<emitter type=\"area\"><color name=\"radiance\" "
      "value=\"-1\"/></emitter></shape>",
      3, "radiance");
}

TEST(SceneBuilder, NegativeZeroRadiusIsAZeroRadiusLightWithoutGeometry) {
  auto s = fromXml(R"(<shape type="sphere"><float name="radius" value="-0"/>
                      <emitter type="area"><color name="radiance" value="1"/></emitter></shape>)");
  EXPECT_EQ(s.scene->sphereLights.size(), 1u);
  EXPECT_EQ(s.scene->geometry.sphereCount(), 0u);
}

TEST(SceneBuilder, UnusedPropertiesBecomeWarningsWithLines) {
  auto s = fromXml(
      "<integrator type=\"direct\">\n<string name=\"measure\" value=\"area\"/>\n"
      "<string name=\"warp-type\" value=\"cosine-hemisphere\"/></integrator>");
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("t.xml:4"), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("warp-type"), std::string::npos);
}

TEST(SceneBuilder, SmallScenesPayForNoBvh) {
  LoadedScene s = loadSceneFromString(defaultSceneXml(), "default", ".");
  EXPECT_FALSE(s.scene->geometry.usesEmbree());
  auto rock = fromXml(R"(<shape type="rock"><integer name="subdivisions" value="3"/></shape>)");
  EXPECT_TRUE(rock.scene->geometry.usesEmbree());
}

TEST(SceneBuilder, OverridesReachTheSettings) {
  LoadedScene s = loadSceneFromString(defaultSceneXml(), "default", ".",
                                      {{"integrator.measure", "area"}, {"sampler.sampleCount", "7"}});
  EXPECT_EQ(s.settings.integrator.strategy, Strategy::DirectArea);
  EXPECT_EQ(s.settings.sampleCount, 7u);
}

}  // namespace
}  // namespace penumbra
