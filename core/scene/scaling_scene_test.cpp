#include "core/scene/scaling_scene.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "core/math/error.h"
#include "core/render/engine.h"
#include "core/scene/scene_builder.h"

namespace penumbra {
namespace {

TEST(ScalingScene, SpheresAreDeterministicAboveTheFloorAndAlternateLightsAndBlockers) {
  for (int n : {1, 7, 100}) {
    const auto a = scalingSceneSpheres(n, 3), b = scalingSceneSpheres(n, 3), c = scalingSceneSpheres(n, 4);
    ASSERT_EQ(a.size(), size_t(2 * n));
    for (size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].sphere.center, b[i].sphere.center);
      EXPECT_GT(a[i].sphere.center.y - a[i].sphere.radius, 0.f);
      EXPECT_LE(std::abs(a[i].sphere.center.x), 10.f);
      EXPECT_LE(std::abs(a[i].sphere.center.z), 10.f);
      EXPECT_EQ(a[i].radiance.x > 0.f, i % 2 == 0) << i;
    }
    EXPECT_NE(a[0].sphere.center, c[0].sphere.center);
  }
}

TEST(ScalingScene, LoadsWithItsLightsAndSpheres) {
  LoadedScene s = loadSceneFromString(scalingSceneXml(50, 16, 2), "scaling", ".");
  EXPECT_EQ(s.scene->sphereLights.size(), 50u);
  EXPECT_EQ(s.scene->geometry.sphereCount(), 100u);
  EXPECT_EQ(s.settings.camera.width, 16);
  for (const SphereLight& l : s.scene->sphereLights) EXPECT_GE(l.geometryIndex, 0);
}

// Sets PENUMBRA_SPHERE_ACCEL for one scope and restores what it was (a whole run may force the BVH
// path; tests run one at a time within this process).
struct SphereAccelOverride {
  explicit SphereAccelOverride(const char* value) {
    if (const char* old = std::getenv("PENUMBRA_SPHERE_ACCEL")) {
      previous = old;
      hadPrevious = true;
    }
    setenv("PENUMBRA_SPHERE_ACCEL", value, 1);
  }
  ~SphereAccelOverride() {
    if (hadPrevious)
      setenv("PENUMBRA_SPHERE_ACCEL", previous.c_str(), 1);
    else
      unsetenv("PENUMBRA_SPHERE_ACCEL");
  }
  std::string previous;
  bool hadPrevious = false;
};

Image renderScaling(const char* accel, const char* measure, bool expectBvh) {
  SphereAccelOverride env(accel);
  LoadedScene s =
      loadSceneFromString(scalingSceneXml(40, 24, 3), "scaling", ".", {{"integrator.measure", measure}});
  EXPECT_EQ(s.scene->geometry.spheresUseBvh(), expectBvh);
  RenderSettings settings = s.settings;
  settings.seed = 5;
  const RenderLimits limits{3, 0.0};
  Engine engine;
  engine.start(std::make_shared<const RenderJob>(s.scene, settings, limits), limits, 2);
  engine.wait();
  return engine.film().mean(3);
}

// The BVH calls the same sphere test as the flat loop, so both find the same hits with the same t:
// the images are bit-identical, for nearest-hit (hemisphere) and shadow-ray (area, solid angle,
// projected solid angle) use.
TEST(ScalingScene, SphereBvhAndBruteForceRenderBitIdenticalImages) {
  for (const char* measure : {"solid-angle", "area", "projected-solid-angle", "hemisphere"}) {
    const Image brute = renderScaling("brute-force", measure, false);
    const Image bvh = renderScaling("bvh", measure, true);
    const Image automatic = renderScaling("auto", measure, true);  // 80 spheres: above the threshold
    ASSERT_EQ(brute.rgb.size(), bvh.rgb.size());
    size_t lit = 0;
    for (float v : brute.rgb) lit += v > 0.f;
    EXPECT_GT(lit, brute.rgb.size() / 20) << measure;
    EXPECT_TRUE(brute.rgb == bvh.rgb) << measure;
    EXPECT_TRUE(brute.rgb == automatic.rgb) << measure;
  }
}

TEST(ScalingScene, BadSphereAccelValueIsAnError) {
  SphereAccelOverride env("fast");
  EXPECT_THROW(loadSceneFromString(scalingSceneXml(2, 8, 1), "scaling", "."), Error);
}

}  // namespace
}  // namespace penumbra
