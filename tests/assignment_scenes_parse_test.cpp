// Every scene XML shipped under scenes/ parses, and the meshes they reference load (except the
// known-missing ajax.obj).
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>

#include "core/math/error.h"
#include "core/scene/light_selection_default.h"
#include "core/scene/obj_loader.h"
#include "core/scene/scene_builder.h"
#include "core/scene/xml_parser.h"
#include "tests/test_support.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

TEST(AssignmentScenes, AllParseAndMeshesLoad) {
  std::vector<std::string> files = test::assignmentSceneFiles();
  EXPECT_EQ(files.size(), 22u);
  int missingAjax = 0;
  for (const std::string& f : files) {
    SCOPED_TRACE(f);
    SceneNode root;
    ASSERT_NO_THROW(root = parseSceneFile(f));
    EXPECT_EQ(root.tag, "scene");
    EXPECT_NE(root.child("camera"), nullptr);
    EXPECT_NE(root.child("integrator"), nullptr);
    EXPECT_NE(root.child("sampler"), nullptr);
    for (const SceneNode& s : root.children) {
      if (s.tag != "shape" || s.type != "obj") continue;
      std::string name = s.props.getString({"filename"}, "");
      std::string path = resolveScenePath(s, name);
      glm::mat4 toWorld = s.props.getTransform({"toWorld"}, glm::mat4(1.f));
      if (fs::path(name).filename() == "ajax.obj") {
        EXPECT_THROW(loadObjMesh(path, toWorld, s.file, s.line), Error);
        ++missingAjax;
        continue;
      }
      TriangleMesh m;
      ASSERT_NO_THROW(m = loadObjMesh(path, toWorld, s.file, s.line)) << path;
      EXPECT_FALSE(m.triangles.empty());
    }
    // Round trip through the writer keeps the structure.
    SceneNode again = parseSceneString(writeSceneXml(root), f, root.baseDir);
    EXPECT_EQ(again.children.size(), root.children.size());
  }
  EXPECT_EQ(missingAjax, 3);
}

// The assignment's scenes have one or two sphere lights: with either light measure the builder keeps
// sampling every light (the light-count default), as the assignment does.
TEST(AssignmentScenes, LightSamplingMeasuresSampleEveryLight) {
  int lit = 0;
  for (const std::string& f : test::assignmentSceneFiles()) {
    SCOPED_TRACE(f);
    SceneNode root = parseSceneFile(f);
    EXPECT_LE(countSphereLights(root), 2u);
    if (countSphereLights(root) > 0) ++lit;
    for (const char* measure : {"", "area", "solid-angle", "projected-solid-angle"}) {
      SceneNode d = root;
      if (*measure) {
        applyOverride(d, "integrator.type", "direct");
        applyOverride(d, "integrator.measure", measure);
      }
      const IntegratorDesc s = buildSettings(d).integrator;
      if (s.usesLightSelection()) {
        EXPECT_EQ(s.lightSelection, LightSelection::All) << measure;
      }
    }
  }
  EXPECT_GT(lit, 0);
}

TEST(AssignmentScenes, AliasSpellingsAreVisible) {
  std::string dir = test::sourcePath("scenes/");
  SceneNode early = parseSceneFile(dir + "hw2/Early-2017-08-30/Tests/sphere-area.xml");
  const SceneNode* integ = early.child("integrator");
  ASSERT_NE(integ, nullptr);
  EXPECT_EQ(integ->props.getInteger({"nSamples", "shadingSamples"}, 0), 1);
  EXPECT_EQ(integ->props.getString({"measure"}, ""), "solidAngle");
  SceneNode ao = parseSceneFile(dir + "hw2/Tests/sphere-ao.xml");
  EXPECT_EQ(ao.child("integrator")->props.getString({"sampler", "sampling", "warp-type", "warp"}, ""),
            "cosine-hemisphere");
  EXPECT_EQ(ao.child("sampler")->props.getInteger({"sampleCount"}, 0), 1024);
  EXPECT_EQ(ao.child("sampler")->props.lineOf({"sampleCount"}), 4);
}

}  // namespace
}  // namespace penumbra
