#include "app/ui/convergence_tracker.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include "app/ui/viewer_controller.h"
#include "core/image/image_io.h"
#include "core/scene/scene_builder.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

// The viewer's live tracker (no GL): one curve per accumulation, kept across strategy switches.
TEST(ConvergenceTracker, KeepsOneCurvePerStrategy) {
  LoadedScene scene = loadScene(PENUMBRA_SOURCE_DIR "/scenes/analytic/plane-sphere-light.xml",
                                {{"camera.width", "48"}, {"camera.height", "48"}});
  ui::ViewerController c(std::move(scene), {}, 2);
  ui::ConvergenceTracker t;
  RenderSettings s = c.settings();
  s.integrator = withCountsOf(directByLight(LightMeasure::Area), s.integrator);
  c.setSettings(s);
  c.setLimits(RenderLimits{256, 0});
  c.start();
  auto drive = [&] {
    for (int i = 0; i < 4000 && !(c.progress().finished && c.snapshot().spp == c.progress().spp); ++i) {
      c.pollSnapshot(false);
      t.update(c);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    c.pollSnapshot(false);
    t.update(c);
  };
  drive();
  ASSERT_TRUE(t.hasReference()) << t.error();
  EXPECT_EQ(t.reference().source, "closed-form");
  ASSERT_EQ(t.curves().size(), 1u);
  s.integrator = withCountsOf(directByLight(LightMeasure::SolidAngle), s.integrator);
  c.setSettings(s);
  c.start();
  drive();
  ASSERT_EQ(t.curves().size(), 2u);
  EXPECT_EQ(t.curves()[0].label, "direct/area");
  EXPECT_EQ(t.curves()[1].label, "direct/solid-angle");
  for (const ui::ConvergenceCurve& curve : t.curves()) {
    ASSERT_GE(curve.rmse.size(), 3u) << curve.label;
    EXPECT_LT(curve.rmse.back(), curve.rmse.front()) << curve.label;  // a few spp -> 256 spp
  }
  // Solid-angle sampling beats area sampling on this scene by far at equal spp.
  EXPECT_LT(t.curves()[1].rmse.back(), t.curves()[0].rmse.back());
  // A reference of the wrong size is refused with a message.
  std::string bad = (fs::temp_directory_path() / "penumbra-bad-ref.pfm").string();
  writeImage(bad, Image(8, 8));
  EXPECT_FALSE(t.loadReference(c, bad));
  EXPECT_NE(t.error().find("8x8"), std::string::npos) << t.error();
  fs::remove(bad);
}

}  // namespace
}  // namespace penumbra
