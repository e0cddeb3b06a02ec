#include "core/scene/scene_builder.h"

#include <gtest/gtest.h>

#include "core/math/error.h"
#include "core/render/strategy_axes.h"

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
  EXPECT_EQ(strategyLabel(ao.settings.integrator), strategyLabel(aoBy(HemisphereWarp::Uniform)));
  EXPECT_EQ(ao.settings.integrator.samples, 4);
  auto ao2 = fromXml(R"(<integrator type="ao"><integer name="nSamples" value="2"/>
                        <string name="warp-type" value="cosine-hemisphere"/></integrator>)");
  EXPECT_EQ(ao2.settings.integrator.samples, 2);
  EXPECT_EQ(strategyLabel(ao2.settings.integrator), strategyLabel(aoBy(HemisphereWarp::Cosine)));
  auto d = fromXml(R"(<integrator type="direct"><integer name="nSamples" value="3"/>
                      <string name="measure" value="solidAngle"/></integrator>)");
  EXPECT_EQ(strategyLabel(d.settings.integrator), strategyLabel(directByLight(LightMeasure::SolidAngle)));
  auto h = fromXml(R"(<integrator type="direct"><string name="measure" value="hemisphere"/>
                      <string name="warp-type" value="uniform-hemisphere"/></integrator>)");
  EXPECT_EQ(strategyLabel(h.settings.integrator), strategyLabel(directByHemisphere(HemisphereWarp::Uniform)));
}

// <integrator type="T"> with the given string properties and, if samplesName is set, 3 samples.
std::string integratorXml(const IntegratorDesc& d,
                          const std::vector<std::pair<std::string_view, std::string_view>>& props,
                          std::string_view samplesName) {
  std::string xml = "<integrator type=\"" + std::string(nameOf(d.type)) + "\">";
  if (!samplesName.empty()) xml += "<integer name=\"" + std::string(samplesName) + "\" value=\"3\"/>";
  for (auto [name, value] : props)
    xml += "<string name=\"" + std::string(name) + "\" value=\"" + std::string(value) + "\"/>";
  return xml + "</integrator>";
}

// The spellings of a selecting property named `canonical`, and of its value `value`.
const Spellings& propertySpellings(std::string_view canonical) {
  for (const Spellings* p : {&kMeasureProperty, &kWarpProperty, &kLightSelectionProperty,
                             &kLightMeasureProperty, &kHeuristicProperty})
    if (p->canonical() == canonical) return *p;
  throw Error("no property " + std::string(canonical));
}
template <class Row, size_t N>
const Spellings* spellingsIn(const std::array<Row, N>& table, Spellings Row::*field, std::string_view value) {
  for (const Row& r : table)
    if ((r.*field).accepts(value)) return &(r.*field);
  return nullptr;
}
const Spellings& valueSpellings(std::string_view property, std::string_view value) {
  const Spellings* found = nullptr;
  if (property == kMeasureProperty.canonical()) {
    for (const EstimatorRow& e : kEstimators)
      if (e.measure.accepts(value)) found = &e.measure;
    if (!found) found = spellingsIn(kLightMeasures, &LightMeasureRow::spellings, value);
  } else if (property == kWarpProperty.canonical()) {
    found = spellingsIn(kWarps, &WarpRow::spellings, value);
  } else if (property == kLightSelectionProperty.canonical()) {
    found = spellingsIn(kLightSelections, &LightSelectionRow::spellings, value);
  } else if (property == kLightMeasureProperty.canonical()) {
    found = spellingsIn(kLightMeasures, &LightMeasureRow::spellings, value);
  } else {
    found = spellingsIn(kHeuristics, &HeuristicRow::spellings, value);
  }
  if (!found) throw Error("no value " + std::string(value) + " of " + std::string(property));
  return *found;
}

// Every spelling the axis tables accept loads its strategy: each alias of each selecting property's
// name and value (the others canonical), each alias of the samples property, and each property left
// out whose value is the one assumed when absent.
TEST(SceneBuilder, EverySpellingOfEveryStrategyLoadsIt) {
  const IntegratorDesc defaults;
  for (const IntegratorDesc& d : everyStrategy()) {
    std::vector<std::pair<std::string_view, std::string_view>> canonical;
    std::vector<std::string> values;  // canonicalProperties' strings, kept alive for the views
    for (const CanonicalProperty& p : canonicalProperties(d))
      if (!p.isInteger) values.push_back(p.value);
    size_t v = 0;
    for (const CanonicalProperty& p : canonicalProperties(d))
      if (!p.isInteger) canonical.emplace_back(p.name, values[v++]);
    auto expectStrategy = [&](const std::string& xml, bool samples) {
      LoadedScene s = fromXml(xml);
      EXPECT_EQ(strategyLabel(s.settings.integrator), strategyLabel(d)) << xml;
      EXPECT_EQ(s.settings.integrator.samples, samples ? 3 : 1) << xml;
      EXPECT_TRUE(s.warnings.empty()) << xml << ": " << (s.warnings.empty() ? "" : s.warnings[0]);
    };
    const Spellings& samples = rowOf(d.type).samplesProperty;
    expectStrategy(integratorXml(d, canonical, samples.canonical()), !samples.empty());
    for (std::string_view name : samples.list()) expectStrategy(integratorXml(d, canonical, name), true);
    for (size_t i = 0; i < canonical.size(); ++i) {
      const Spellings& property = propertySpellings(canonical[i].first);
      for (std::string_view name : property.list())
        for (std::string_view value : valueSpellings(canonical[i].first, canonical[i].second).list()) {
          auto props = canonical;
          props[i] = {name, value};
          expectStrategy(integratorXml(d, props, {}), false);
        }
      // Left out: IntegratorDesc's defaults are the values assumed.
      const std::pair<std::string_view, std::string_view> assumed[] = {
          {kMeasureProperty.canonical(), measureName(defaults)},
          {kWarpProperty.canonical(), nameOf(defaults.warp)},
          {kLightSelectionProperty.canonical(), nameOf(defaults.lightSelection)},
          {kLightMeasureProperty.canonical(), nameOf(defaults.lightMeasure)},
          {kHeuristicProperty.canonical(), nameOf(defaults.heuristic)}};
      for (const auto& [name, value] : assumed)
        if (canonical[i].first == name && canonical[i].second == value) {
          auto props = canonical;
          props.erase(props.begin() + long(i));
          expectStrategy(integratorXml(d, props, {}), false);
        }
    }
  }
}

// What the viewer writes (canonical spellings) loads back to the same strategy and counts.
TEST(SceneBuilder, CanonicalSpellingsRoundTrip) {
  for (IntegratorDesc d : everyStrategy()) {
    if (d.usesSamples()) d.samples = 5;
    if (d.usesMisAxes()) d.lightSamples = 3, d.bsdfSamples = 2;
    std::string xml = "<integrator type=\"" + std::string(nameOf(d.type)) + "\">";
    for (const CanonicalProperty& p : canonicalProperties(d))
      xml += std::string(p.isInteger ? "<integer" : "<string") + " name=\"" + std::string(p.name) +
             "\" value=\"" + p.value + "\"/>";
    xml += "</integrator>";
    EXPECT_EQ(fromXml(xml).settings.integrator, d) << xml;
  }
}

TEST(SceneBuilder, MisCountsDefaultToOneAndMustBePositive) {
  const IntegratorDesc d =
      fromXml("<integrator type=\"direct\"><string name=\"measure\" value=\"mis\"/></integrator>")
          .settings.integrator;
  EXPECT_EQ(strategyLabel(d), strategyLabel(directByMis(LightMeasure::SolidAngle, MisHeuristic::Power)));
  EXPECT_EQ(d.lightSamples, 1);
  EXPECT_EQ(d.bsdfSamples, 1);
  expectError(
      "<integrator type=\"direct\"><string name=\"measure\" value=\"mis\"/>\n"
      "<integer name=\"bsdfSamples\" value=\"0\"/></integrator>",
      3, "bsdfSamples");
}

TEST(SceneBuilder, UnknownStrategiesAreRejectedWithWhatIsAccepted) {
  expectError("<integrator type=\"path\"/>", 2, "(expected one of: direct, ao, simple, normals)");
  expectError(
      "<integrator type=\"direct\">\n<string name=\"measure\" value=\"solid\"/></integrator>", 3,
      "unknown measure \"solid\" of <integrator type=\"direct\"> (expected one of: hemisphere, bsdf, area, "
      "solid-angle, solidAngle, projected-solid-angle, projectedSolidAngle, mis)");
  expectError("<integrator type=\"ao\">\n<string name=\"sampling\" value=\"area\"/></integrator>", 3,
              "(expected one of: uniform-hemisphere, uniform, cosine-hemisphere, cosine)");
  expectError(
      "<integrator type=\"direct\"><string name=\"measure\" value=\"hemisphere\"/>\n"
      "<string name=\"warp\" value=\"beckmann\"/></integrator>",
      3, "unknown warp-type \"beckmann\"");
  expectError("<sampler type=\"halton\"/>", 2, "(expected one of: independent, stratified, sobol, zsobol)");
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

// A negative seed is refused, not wrapped into a 64-bit one.
TEST(SceneBuilder, NegativeSeedIsRejectedWithItsLine) {
  expectError("<sampler type=\"independent\">\n<integer name=\"seed\" value=\"-1\"/></sampler>", 3,
              "seed must be an integer >= 0, got -1");
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
  EXPECT_EQ(strategyLabel(s.settings.integrator), strategyLabel(directByLight(LightMeasure::Area)));
  EXPECT_EQ(s.settings.sampleCount, 7u);
}

// A --set value the builder refuses is blamed on the --set, not on a line of the file (the file's
// line holds a valid value).
std::string loadError(const std::string& xml, std::vector<std::pair<std::string, std::string>> sets) {
  try {
    loadSceneFromString(xml, "scene.xml", ".", sets);
  } catch (const Error& e) {
    return e.what();
  }
  return "(loaded)";
}

TEST(SceneBuilder, InvalidSetValuesAreBlamedOnTheSet) {
  const std::string xml =
      "<scene>\n<integrator type=\"direct\">\n<string name=\"measure\" value=\"area\"/>\n</integrator>\n"
      "<sampler type=\"independent\">\n<integer name=\"sampleCount\" value=\"4\"/>\n</sampler>\n"
      "<camera type=\"perspective\">\n<float name=\"fov\" value=\"30\"/>\n</camera>\n"
      "<shape type=\"sphere\"/>\n</scene>\n";
  ASSERT_EQ(loadError(xml, {}), "(loaded)");
  // A value of the file's type that the builder refuses.
  EXPECT_EQ(loadError(xml, {{"sampler.sampleCount", "0"}}),
            "--set sampler.sampleCount=0: sampleCount must be an integer in [1, 16777216], got 0");
  EXPECT_EQ(loadError(xml, {{"camera.fov", "200"}}).rfind("--set camera.fov=200: fov must be in (0, 180)", 0),
            0u);
  EXPECT_EQ(loadError(xml, {{"integrator.measure", "bogus"}})
                .rfind("--set integrator.measure=bogus: unknown measure", 0),
            0u);
  // A value that does not parse as the file's type.
  std::string m = loadError(xml, {{"sampler.sampleCount", "many"}});
  EXPECT_EQ(m.rfind("--set sampler.sampleCount=many: cannot set property \"sampleCount\"", 0), 0u) << m;
  // A property the file does not have, and an object type.
  m = loadError(xml, {{"integrator.nSamples", "zero"}});
  EXPECT_EQ(m.rfind("--set integrator.nSamples=zero: ", 0), 0u) << m;
  m = loadError(xml, {{"integrator.type", "bogus"}});
  EXPECT_EQ(m.rfind("--set integrator.type=bogus: unknown integrator type \"bogus\"", 0), 0u) << m;
  // The same values in the file are still blamed on their lines.
  std::string inFile = xml;
  inFile.replace(inFile.find("value=\"4\""), 9, "value=\"0\"");
  EXPECT_EQ(loadError(inFile, {}).rfind("scene.xml:6: sampleCount must be", 0), 0u) << loadError(inFile, {});
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

const char* kRectangleLight = R"(<shape type="rectangle">
  <transform name="toWorld"><scale value="2, 0.5, 1"/><rotate axis="1, 0, 0" angle="180"/>
    <translate value="0, 0, 3"/></transform>
  <emitter type="area"><color name="radiance" value="4, 5, 6"/></emitter></shape>)";

TEST(SceneBuilderPolygonLights, ARectangleIsOneParallelogramLightFacingItsTransformedNormal) {
  auto s = fromXml(kRectangleLight);
  ASSERT_EQ(s.scene->polygonLights.size(), 1u);
  const PolygonLight& light = s.scene->polygonLights[0];
  EXPECT_TRUE(light.parallelogram);
  EXPECT_NEAR(light.area, 4.f * 2.f * 0.5f, 1e-5f);
  EXPECT_NEAR(light.n.z, -1.f, 1e-6f);  // +z turned over: it faces down
  EXPECT_EQ(light.radiance, Color3(4, 5, 6));
  EXPECT_EQ(s.scene->areaLightCount(), 1u);
  EXPECT_TRUE(s.scene->hasAreaLights());
  ASSERT_EQ(s.scene->polygonLightOfPrim.size(), 2u);  // both triangles belong to it
  EXPECT_EQ(s.scene->polygonLightOfPrim[0], 0);
  EXPECT_EQ(s.scene->polygonLightOfPrim[1], 0);
  EXPECT_TRUE(s.scene->materials[0].emits());
}

TEST(SceneBuilderPolygonLights, EveryTriangleOfAMeshEmitsAndLightsMixInOneScene) {
  auto s = fromXml(std::string(kRectangleLight) + R"(
    <shape type="rock"><integer name="subdivisions" value="0"/>
      <emitter type="area"><color name="radiance" value="1"/></emitter></shape>
    <shape type="plane"><emitter type="area"><color name="radiance" value="2"/></emitter></shape>
    <shape type="sphere"><point name="center" value="0, 0, 9"/>
      <emitter type="area"><color name="radiance" value="1"/></emitter></shape>
    <emitter type="point"><point name="position" value="0, 0, 5"/></emitter>)");
  EXPECT_EQ(s.scene->sphereLights.size(), 1u);
  EXPECT_EQ(s.scene->polygonLights.size(), 1u + 20u + 1u);  // rectangle, the rock's 20 triangles, plane
  EXPECT_EQ(s.scene->areaLightCount(), 23u);
  EXPECT_EQ(s.scene->uniformSelection.count, 23u);
  EXPECT_EQ(s.scene->lightBvh.leafOf.size(), 23u);
  EXPECT_EQ(s.scene->pointLights.size(), 1u);
  for (const PolygonLight& l : s.scene->polygonLights) EXPECT_TRUE(l.valid());
}

TEST(SceneBuilderPolygonLights, BadEmittersAreErrorsWithTheirLine) {
  expectError(
      "<shape type=\"rectangle\">\n<transform name=\"toWorld\"><scale value=\"1, 0, 1\"/></transform>"
      "</shape>",
      3, "singular");
  expectError(
      "<shape type=\"rectangle\">\n<emitter type=\"area\"><color name=\"radiance\" value=\"-1\"/>"
      "</emitter></shape>",
      3, "radiance");
  expectError(
      "<shape type=\"rectangle\">\n<emitter type=\"area\"><color name=\"radiance\" value=\"nan\"/>"
      "</emitter></shape>",
      3, "radiance");
  expectError("<shape type=\"plane\">\n<emitter type=\"spot\"/></shape>", 3, "spot");
  expectError(
      "<shape type=\"rock\">\n<transform name=\"toWorld\"><scale value=\"3e38\"/><translate value=\"3e38, 0, "
      "0\"/></transform>\n"
      "<emitter type=\"area\"/></shape>",
      3, "float range");
  // Finite vertices whose triangles' areas overflow.
  expectError(
      "<shape type=\"rock\">\n<transform name=\"toWorld\"><scale value=\"1e38\"/></transform>\n"
      "<emitter type=\"area\"/></shape>",
      4, "zero or non-finite area");
  expectError("\n<emitter type=\"area\"/>", 3, "inside the shape");
}

}  // namespace
}  // namespace penumbra
