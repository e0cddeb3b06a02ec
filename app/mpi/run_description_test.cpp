#include "app/mpi/run_description.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/math/temp_dir_test_support.h"
#include "core/scene/scene_builder.h"

namespace penumbra::mpi {
namespace {

namespace fs = std::filesystem;

const std::string kSphereArea = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/hw2/Tests/sphere-area.xml";

RunChoices choices(uint32_t block = 16, uint64_t spp = 64) {
  return RunChoices{spp, 0.0, block, false, "exr"};
}

RunDescription describe(const std::string& path,
                        const std::vector<std::pair<std::string, std::string>>& sets = {},
                        const RunChoices& c = choices()) {
  const LoadedScene loaded = loadScene(path, sets);
  return describeRun(loaded.settings, c, loaded.desc);
}

TEST(RunDescription, TheSameRunHasTheSameDigestAndNoDifference) {
  const RunDescription a = describe(kSphereArea), b = describe(kSphereArea);
  EXPECT_EQ(digestOf(a), digestOf(b));
  EXPECT_EQ(firstDifference(a, b), "");
}

TEST(RunDescription, NamesTheSettingThatDiffersWithTheRanksValueFirst) {
  const RunDescription root = describe(kSphereArea, {{"camera.width", "128"}, {"camera.height", "128"}});
  const RunDescription mine = describe(kSphereArea, {{"camera.width", "64"}, {"camera.height", "64"}});
  EXPECT_NE(digestOf(mine), digestOf(root));
  EXPECT_EQ(firstDifference(mine, root), " on camera.width: 64 vs 128");
  EXPECT_EQ(firstDifference(describe(kSphereArea, {}, choices(8)), describe(kSphereArea)),
            " on block: 8 vs 16");
  EXPECT_EQ(firstDifference(describe(kSphereArea, {}, choices(16, 32)), describe(kSphereArea)),
            " on spp: 32 vs 64");
  EXPECT_EQ(firstDifference(describe(kSphereArea, {{"sampler.seed", "5"}}), describe(kSphereArea)),
            " on seed: 5 vs 0");
  EXPECT_EQ(firstDifference(describe(kSphereArea, {{"sampler.type", "stratified"}}), describe(kSphereArea)),
            " on sampler.type: stratified vs independent");
  EXPECT_EQ(
      firstDifference(describe(kSphereArea, {{"integrator.measure", "solid-angle"}}), describe(kSphereArea)),
      " on integrator.measure: solid-angle vs area");
  RunChoices timed = choices(16, 0);
  timed.seconds = 2.5;
  EXPECT_EQ(firstDifference(describe(kSphereArea, {}, timed), describe(kSphereArea, {}, choices(16, 0))),
            " on time: 2.5 s vs none");
}

TEST(RunDescription, SceneContentOutsideTheSettingsIsCaughtAndPlaced) {
  const RunDescription root = describe(kSphereArea);
  const RunDescription mine = describe(kSphereArea, {{"emitter.radiance", "1,1,1"}});
  EXPECT_NE(digestOf(mine), digestOf(root));
  EXPECT_EQ(firstDifference(mine, root), ": the resolved scene differs at emitter.radiance (" + kSphereArea +
                                             ":18): 1, 1, 1 vs 300, 300, 300");
  EXPECT_EQ(firstDifference(describe(kSphereArea, {{"shape.radius", "0.2"}}), root),
            ": the resolved scene differs at shape.radius (" + kSphereArea + ":16): 0.2 vs 0.1");
}

class RunDescriptionFiles : public test::TempDirTest {
 protected:
  RunDescriptionFiles() : TempDirTest("penumbra-run-description-") {}
  // A copy of the sphere-area scene and its plane.obj in dir/name.
  std::string copyScene(const std::string& name) {
    const fs::path to = dir / name, from = fs::path(kSphereArea).parent_path();
    fs::create_directories(to);
    fs::copy_file(kSphereArea, to / "sphere-area.xml");
    fs::copy_file(from / "plane.obj", to / "plane.obj");
    return (to / "sphere-area.xml").string();
  }
};

TEST_F(RunDescriptionFiles, TheSameFilesUnderOtherPathsAgreeAndADifferentObjIsNamed) {
  const std::string a = copyScene("a"), b = copyScene("b");
  EXPECT_EQ(digestOf(describe(a)), digestOf(describe(b)));
  EXPECT_EQ(digestOf(describe(a)), digestOf(describe(kSphereArea)));
  std::ofstream(dir / "b" / "plane.obj", std::ios::app) << "v 0 0 5\n";
  const std::string difference = firstDifference(describe(b), describe(a));
  EXPECT_EQ(difference.rfind(": the resolved scene differs at shape#3.filename (contents) (" + a + ":31, " +
                                 (dir / "a" / "plane.obj").string() + "): fnv1a64 ",
                             0),
            0u)
      << difference;
}

TEST_F(RunDescriptionFiles, PropertyOrderDoesNotMatterButObjectsDo) {
  const std::string head = "<scene><camera type=\"perspective\">";
  const std::string tail =
      "</camera><shape type=\"sphere\"><float name=\"radius\" value=\"1\"/></shape></scene>";
  const std::string wh = "<integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"6\"/>";
  const std::string hw = "<integer name=\"height\" value=\"6\"/><integer name=\"width\" value=\"8\"/>";
  auto fromXml = [](const std::string& xml) {
    const LoadedScene loaded = loadSceneFromString(xml, "s.xml", ".");
    return describeRun(loaded.settings, choices(), loaded.desc);
  };
  EXPECT_EQ(digestOf(fromXml(head + wh + tail)), digestOf(fromXml(head + hw + tail)));
  const std::string extra = "<shape type=\"sphere\"><float name=\"radius\" value=\"2\"/></shape></scene>";
  const std::string twoShapes = head + wh + tail.substr(0, tail.size() - 8) + extra;
  EXPECT_EQ(firstDifference(fromXml(twoShapes), fromXml(head + wh + tail)),
            ": the resolved scene differs at shape#2 (s.xml:1): sphere vs (absent)");
  EXPECT_EQ(firstDifference(fromXml(head + wh + tail), fromXml(twoShapes)),
            ": the resolved scene differs at shape#2 (s.xml:1): (absent) vs sphere");
}

TEST(RunDescription, SerializationKeepsEveryField) {
  RunDescription d = describe(kSphereArea, {{"emitter.radiance", "1,2,3"}});
  d.push_back({"odd: name 12:", "", "x:1", true});
  d.push_back({"", "value with\nnewline", "", false});
  const RunDescription back = deserialize(serialize(d));
  ASSERT_EQ(back.size(), d.size());
  for (size_t i = 0; i < d.size(); ++i) {
    EXPECT_EQ(back[i].name, d[i].name);
    EXPECT_EQ(back[i].value, d[i].value);
    EXPECT_EQ(back[i].where, d[i].where);
    EXPECT_EQ(back[i].inScene, d[i].inScene);
  }
  EXPECT_EQ(digestOf(back), digestOf(d));
}

TEST(RunDescription, DigestSeparatesNamesFromValues) {
  const RunDescription a = {{"ab", "c", "", false}}, b = {{"a", "bc", "", false}};
  EXPECT_NE(digestOf(a), digestOf(b));
}

}  // namespace
}  // namespace penumbra::mpi
