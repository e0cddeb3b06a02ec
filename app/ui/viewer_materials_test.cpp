// The Materials panel's edits through ViewerController: a glossy BSDF's roughness, kd and distribution
// change the built scene and its description (so Save as keeps them) and restart the render with the
// user's settings kept; a value the scene file would be refused for is refused with the same message
// and the last good scene renders on; diffuse scenes list nothing.
#include <gtest/gtest.h>

#include <string>

#include "app/ui/viewer_controller.h"
#include "core/scene/scene_builder.h"

using namespace penumbra;

namespace {

const char* kGlossyScene = R"(<scene>
  <integrator type="direct"><string name="measure" value="mis"/></integrator>
  <camera type="perspective"><integer name="width" value="24"/><integer name="height" value="16"/></camera>
  <shape type="rectangle"><string name="name" value="plate"/>
    <bsdf type="roughconductor"><float name="alpha" value="0.05"/></bsdf></shape>
  <shape type="sphere"><point name="center" value="0, 0, 1"/><float name="radius" value="0.3"/>
    <bsdf type="microfacet"/></shape>
  <shape type="sphere"><point name="center" value="0.5, 0, 3"/><float name="radius" value="0.2"/>
    <emitter type="area"><color name="radiance" value="5"/></emitter></shape>
</scene>)";

LoadedScene glossyScene() {
  return loadSceneFromString(kGlossyScene, "glossy.xml", ".");
}

}  // namespace

TEST(ViewerMaterials, ListsTheGlossyBsdfsInDocumentOrder) {
  ui::ViewerController c(glossyScene(), {}, 1);
  ASSERT_EQ(c.glossyBsdfEntries().size(), 2u);
  EXPECT_EQ(c.glossyBsdfEntries()[0].label, "shape 0 (rectangle) \"plate\"");
  EXPECT_EQ(c.glossyBsdfEntries()[0].bsdf.type, BsdfType::RoughConductor);
  EXPECT_EQ(c.glossyBsdfEntries()[1].bsdf.type, BsdfType::Microfacet);
  ui::ViewerController diffuse(loadSceneFromString(defaultSceneXml(), "<built-in>", "."), {}, 1);
  EXPECT_TRUE(diffuse.glossyBsdfEntries().empty());
}

TEST(ViewerMaterials, AnEditRebuildsTheSceneKeepsTheSettingsAndIsSaved) {
  ui::ViewerController c(glossyScene(), {}, 1);
  RenderSettings s = c.settings();
  s.seed = 77;  // a live setting the user chose
  c.setSettings(s);
  const auto before = c.scene().scene;
  const uint64_t restarts = c.restartCount();
  ASSERT_TRUE(c.setBsdfProperty(0, "alpha", "0.3"));
  ASSERT_TRUE(c.setBsdfProperty(0, "distribution", "ggx"));
  ASSERT_TRUE(c.setBsdfProperty(1, "kd", "0.1, 0.1, 0.1"));
  EXPECT_NE(c.scene().scene, before);
  EXPECT_GT(c.restartCount(), restarts);
  EXPECT_EQ(c.settings().seed, 77u);
  EXPECT_FLOAT_EQ(c.scene().scene->materials[0].bsdf.alpha, 0.3f);
  EXPECT_EQ(c.scene().scene->materials[0].bsdf.distribution, MicrofacetDistribution::Ggx);
  EXPECT_FLOAT_EQ(c.scene().scene->materials[1].bsdf.albedo.x, 0.1f);
  EXPECT_FLOAT_EQ(c.glossyBsdfEntries()[0].bsdf.alpha, 0.3f);
  // The saved scene carries the edits.
  const LoadedScene saved = loadSceneFromString(c.liveSceneXml(), "saved.xml", ".");
  EXPECT_FLOAT_EQ(saved.scene->materials[0].bsdf.alpha, 0.3f);
  EXPECT_EQ(saved.scene->materials[0].bsdf.distribution, MicrofacetDistribution::Ggx);
  EXPECT_FLOAT_EQ(saved.scene->materials[1].bsdf.ks, 0.9f);
}

TEST(ViewerMaterials, ARefusedValueKeepsTheLastGoodScene) {
  ui::ViewerController c(glossyScene(), {}, 1);
  const auto before = c.scene().scene;
  EXPECT_FALSE(c.setBsdfProperty(0, "alpha", "0.0"));
  EXPECT_NE(c.sceneError().find("alpha (the roughness) must be in [1e-06, 1000], got 0"), std::string::npos)
      << c.sceneError();
  EXPECT_NE(c.sceneError().find("the Materials panel"), std::string::npos) << c.sceneError();
  EXPECT_EQ(c.scene().scene, before);
  EXPECT_FALSE(c.setBsdfProperty(0, "distribution", "phong"));
  EXPECT_FALSE(c.setBsdfProperty(1, "kd", "1.5, 0, 0"));
  EXPECT_FALSE(c.setBsdfProperty(7, "alpha", "0.1"));
  EXPECT_EQ(c.scene().scene, before);
  EXPECT_FLOAT_EQ(c.glossyBsdfEntries()[0].bsdf.alpha, 0.05f);
  // A good value afterwards clears the error.
  EXPECT_TRUE(c.setBsdfProperty(0, "alpha", "0.2"));
  EXPECT_TRUE(c.sceneError().empty());
}
