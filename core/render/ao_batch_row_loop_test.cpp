#include "core/render/ao_batch_row_loop.h"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <thread>

#include "core/geometry/procedural_mesh.h"
#include "core/math/frame.h"
#include "core/render/engine.h"
#include "core/render/packet_kernels.h"
#include "core/render/packet_target_test_support.h"
#include "core/sampling/sampler_table.h"

namespace penumbra {
namespace {

// A rock on a ground plane (both in Embree) beside a sphere in front of the camera, which is in the
// flat loop or in the BVH as `sphereMode` says; the camera also sees the sky, so some lanes of a
// batch miss everything.
std::shared_ptr<const Scene> rockScene(AccelMode sphereMode) {
  auto scene = std::make_shared<Scene>();
  scene->geometry.addMesh(makeRockMesh(3, 7), 0);
  scene->geometry.addMesh(makeGridPlane(Vec3(-20, -1, -20), Vec3(0, 0, 40), Vec3(40, 0, 0), 2, 2), 1);
  scene->geometry.addSphere(Sphere{Vec3(0.9f, -0.6f, 0.8f), 0.4f}, 2);
  for (int i = 0; i < 3; ++i) scene->materials.push_back(SurfaceMaterial{});
  scene->geometry.build(AccelMode::Embree, sphereMode);
  scene->rayLengthBound = scene->geometry.bounds().diagonal() * 1.01f;
  return scene;
}

std::shared_ptr<const RenderJob> aoJob(std::shared_ptr<const Scene> scene, HemisphereWarp warp, int samples,
                                       SamplerKind sampler) {
  RenderSettings s;
  CameraDesc& cam = s.camera;
  const Vec3 origin(2.6f, 1.4f, 3.4f), dir = glm::normalize(Vec3(0.f, -0.2f, 0.f) - origin);
  const Vec3 left = glm::normalize(glm::cross(Vec3(0, 1, 0), dir));
  cam.toWorld = cameraToWorld(origin, left, glm::cross(dir, left), dir);
  cam.fovDegrees = 50.f;
  cam.width = 67;  // not a multiple of any batch
  cam.height = 23;
  s.samplerKind = sampler;
  s.sampleCount = 8;
  s.seed = 11;
  s.integrator = withSamples(aoBy(warp), samples);
  return std::make_shared<RenderJob>(std::move(scene), s, RenderLimits{});
}

Image render(const std::shared_ptr<const RenderJob>& job, bool batched, uint32_t spp) {
  Engine engine;
  if (!batched) engine.setRowRendererFactory(makeScalarRowRenderer);
  engine.start(job, RenderLimits{spp, 0.0}, 2);
  engine.wait();
  return engine.film().mean(spp);
}

using test::ForcedTarget;

// The batch changes only how Embree is asked, and its packets only where the draws and camera rays are
// computed: the same rays, summed in the same order, so the image is the per-sample loop's bit for bit,
// on every instruction set, for every warp, sampler and sample count: in packets 4 and 37 directions
// (batches ending in partial packets) on every instruction set, 300 (a row split into batches of a few
// pixels) and 2,000 (batches of a single pixel) on the best one; one camera sample at a time, more
// directions than a packet carries, on a 9×3 image.
TEST(AoBatchRowLoop, EqualsTheScalarLoopBitForBit) {
  for (const AccelMode sphereMode : {AccelMode::BruteForce, AccelMode::Embree}) {
    const auto scene = rockScene(sphereMode);
    ASSERT_TRUE(scene->geometry.usesEmbree());
    for (const HemisphereWarp warp : {HemisphereWarp::Cosine, HemisphereWarp::Uniform}) {
      for (int k = 0; k < kSamplerKindCount; ++k) {
        const SamplerKind sampler = SamplerKind(k);
        for (const int samples : {4, 37, 300, 2000, kMaxPacketDraws + 1})
          for (const std::string& target : availablePacketTargets()) {
            if (samples > 37 && target != availablePacketTargets().front()) continue;
            ForcedTarget forced(target);
            SCOPED_TRACE(
                target + " " + samplerKindName(sampler) + " samples " + std::to_string(samples) +
                (warp == HemisphereWarp::Cosine ? " cosine" : " uniform") +
                (sphereMode == AccelMode::Embree ? " sphere in the BVH" : " sphere in the flat loop"));
            auto job = std::make_shared<RenderJob>(*aoJob(scene, warp, samples, sampler));
            if (samples > kMaxPacketDraws) job->settings.camera.width = 9, job->settings.camera.height = 3;
            const uint32_t spp = samples > 4 ? 1 : 3;
            const Image batched = render(job, true, spp), scalar = render(job, false, spp);
            EXPECT_EQ(batched.rgb, scalar.rgb);
            double sum = 0;
            for (float v : batched.rgb) sum += v;
            EXPECT_GT(sum, 0.0);  // the scene is visible and lit
          }
      }
    }
  }
}

// Cancelling stops a row between batches: with 20,000 rays per camera sample a batch is one pixel
// (milliseconds), so a cancelled render of a row of 4,096 such pixels (tens of seconds) ends at once.
TEST(AoBatchRowLoop, CancelStopsBetweenBatches) {
  auto job = std::make_shared<RenderJob>(
      *aoJob(rockScene(AccelMode::BruteForce), HemisphereWarp::Cosine, 20000, SamplerKind::Independent));
  job->settings.camera.width = 4096;
  job->settings.camera.height = 1;
  Engine engine;
  engine.start(job, RenderLimits{1, 0.0}, 1);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // inside the row
  const auto start = std::chrono::steady_clock::now();
  engine.cancel();
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  EXPECT_EQ(engine.progress().spp, 0u);
  EXPECT_TRUE(engine.progress().finished);
}

}  // namespace
}  // namespace penumbra
