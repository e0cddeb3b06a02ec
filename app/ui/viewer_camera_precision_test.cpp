// The orbit camera where floats run out of precision, as the monkey test reached it: panned far from
// the world's origin, then dollied onto the target, an orbit must not turn the camera into NaN.
#include <gtest/gtest.h>

#include <cmath>

#include "app/ui/viewer_controller.h"
#include "core/scene/scene_builder.h"

using namespace penumbra;
using namespace penumbra::ui;

namespace {

bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

}  // namespace

TEST(ViewerCameraPrecision, OrbitOfACameraRoundedOntoItsFarTargetStaysFinite) {
  ViewerController c(loadSceneFromString(defaultSceneXml(), "built-in", "."), {}, 1);
  c.setPaused(true);
  c.dolly(-500);     // as far out as the dolly goes
  c.pan(2000, 300);  // a pixel is ~thousands of units there: the target leaves for ~1e6
  c.dolly(500);      // back in to the closest distance, far smaller than a float's spacing at 1e6
  ASSERT_TRUE(finite(c.settings().camera.toWorld));
  for (float dx : {10.f, -40.f, 0.f})
    for (float dy : {0.f, 25.f, -60.f}) {
      c.orbit(dx, dy);
      ASSERT_TRUE(finite(c.settings().camera.toWorld)) << "after orbit(" << dx << ", " << dy << ")";
    }
  c.pan(-5, 5);
  c.dolly(-1);
  EXPECT_TRUE(finite(c.settings().camera.toWorld));
  EXPECT_TRUE(std::isfinite(c.orbitCamera().distance));
}
