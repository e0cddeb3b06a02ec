#include "core/geometry/occlusion_batch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/geometry/procedural_mesh.h"

namespace penumbra {
namespace {

// Rays from just above a ground plane in every direction, past a rock and a sphere, some of them
// empty segments: a batch answers each as SceneGeometry::occluded does, with the sphere in the flat
// loop and in the BVH, and again after clear().
TEST(OcclusionBatch, AnswersAsOccludedDoes) {
  for (const AccelMode sphereMode : {AccelMode::BruteForce, AccelMode::Embree}) {
    SceneGeometry geometry;
    geometry.addMesh(makeRockMesh(3, 7), 0);
    geometry.addMesh(makeGridPlane(Vec3(-20, -1, -20), Vec3(0, 0, 40), Vec3(40, 0, 0), 2, 2), 1);
    geometry.addSphere(Sphere{Vec3(0.9f, -0.6f, 0.8f), 0.4f}, 2);
    geometry.build(AccelMode::Embree, sphereMode);
    OcclusionBatch batch(geometry);
    std::vector<Ray> rays;
    for (int i = 0; i < 400; ++i) {
      const float a = float(i) * 0.0157f, b = float(i % 17) * 0.37f;
      const Vec3 o(3.f * std::cos(a), -0.99f + 0.01f * float(i % 5), 3.f * std::sin(a));
      const Vec3 d = glm::normalize(
          Vec3(std::cos(b) - o.x * 0.3f, 0.2f + 0.1f * float(i % 3), std::sin(b) - o.z * 0.3f));
      rays.push_back(Ray{o, d, 0.f, i % 7 == 0 ? 0.f : 1e3f});  // some empty segments
    }
    for (int round = 0; round < 2; ++round) {  // a batch is reused after clear()
      batch.clear();
      for (const Ray& r : rays) batch.add(r);
      batch.trace();
      ASSERT_EQ(batch.size(), rays.size());
      int blocked = 0;
      for (size_t i = 0; i < rays.size(); ++i) {
        EXPECT_EQ(batch.occluded(i), geometry.occluded(rays[i])) << "ray " << i;
        blocked += batch.occluded(i);
      }
      EXPECT_GT(blocked, 20);
      EXPECT_LT(blocked, 380);
    }
  }
}

}  // namespace
}  // namespace penumbra
