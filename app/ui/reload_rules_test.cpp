// keepUserChanges: a setting the user changed survives a reload unless the file changed it too.
#include "app/ui/reload_rules.h"

#include <gtest/gtest.h>

using namespace penumbra;
using namespace penumbra::ui;

TEST(ReloadRules, TheUsersChangeSurvivesUnlessTheFileChangedTheSameSetting) {
  RenderSettings file;
  file.camera.fovDegrees = 40.f;
  file.seed = 1;
  RenderSettings live = file;
  live.camera.fovDegrees = 50.f;                                                       // the user's camera
  live.integrator = withCountsOf(directByLight(LightMeasure::Area), live.integrator);  // and integrator
  RenderSettings changed = file;
  changed.integrator =
      withCountsOf(aoBy(HemisphereWarp::Cosine), changed.integrator);  // the file changed the integrator
  changed.seed = 7;                                                    // and the sampler

  const ReloadedSettings r = keepUserChanges(file, live, changed);
  EXPECT_EQ(r.settings.camera.fovDegrees, 50.f);
  EXPECT_EQ(strategyLabel(r.settings.integrator), strategyLabel(aoBy(HemisphereWarp::Cosine)));
  EXPECT_EQ(r.settings.seed, 7u);
  EXPECT_EQ(r.kept, std::vector<std::string>{"camera"});

  const ReloadedSettings same = keepUserChanges(file, live, file);
  EXPECT_EQ(same.kept, (std::vector<std::string>{"camera", "integrator"}));
  EXPECT_EQ(reloadStatus("a.xml", same.kept), "reloaded a.xml; kept your camera, integrator");
  EXPECT_EQ(reloadStatus("a.xml", {}), "reloaded a.xml");
  EXPECT_TRUE(keepUserChanges(file, file, changed).kept.empty());
}
