// RenderOutput::MisLightShare through the engine: MIS's split film against their ordinary
// image, pixel by pixel, for the same seed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/geometry/procedural_mesh.h"
#include "core/integrators/mis_light_share.h"
#include "core/math/frame.h"
#include "core/render/engine.h"

namespace penumbra {
namespace {

void addLight(Scene& scene, const Vec3& c, float r, float Le) {
  SphereLight light;
  light.sphere = Sphere{c, r};
  light.radiance = Color3(Le);
  light.geometryIndex = int32_t(scene.geometry.addSphere(light.sphere, uint32_t(scene.materials.size())));
  SurfaceMaterial emitter;
  emitter.sphereLight = int32_t(scene.sphereLights.size());
  scene.sphereLights.push_back(light);
  scene.materials.push_back(emitter);
}

// A floor, a diffuse sphere, a large light near the floor and a small bright one, a point light.
std::shared_ptr<const Scene> twoLightScene() {
  auto scene = std::make_shared<Scene>();
  addLight(*scene, Vec3(1.5f, -1.f, -0.3f), 0.6f, 4.f);
  addLight(*scene, Vec3(-1.f, 1.f, 2.f), 0.05f, 800.f);
  scene->geometry.addSphere(Sphere{Vec3(0.f), 0.7f}, uint32_t(scene->materials.size()));
  scene->materials.push_back(SurfaceMaterial{});
  scene->geometry.addMesh(makeGridPlane(Vec3(-50, -50, -1), Vec3(100, 0, 0), Vec3(0, 100, 0), 1, 1),
                          uint32_t(scene->materials.size()));
  scene->materials.push_back(SurfaceMaterial{});
  scene->pointLights.push_back(PointLight{Vec3(0.f, -2.f, 2.f), Color3(3.f, 2.f, 1.f)});
  scene->geometry.build();
  scene->rayLengthBound = scene->geometry.bounds().diagonal() * 1.01f;
  return scene;
}

std::shared_ptr<RenderJob> job(const IntegratorDesc& strategy, RenderOutput output) {
  RenderSettings s;
  CameraDesc& cam = s.camera;
  const Vec3 origin(4, 4, 1.5f), dir = glm::normalize(Vec3(0.f, 0.f, -0.5f) - origin);
  const Vec3 left = glm::normalize(glm::cross(Vec3(0, 0, 1), dir));
  cam.toWorld = cameraToWorld(origin, left, glm::cross(dir, left), dir);
  cam.fovDegrees = 50.f;
  cam.width = 40;
  cam.height = 30;
  s.seed = 7;
  s.integrator = strategy;
  s.integrator.lightSamples = 2;
  return std::make_shared<RenderJob>(twoLightScene(), s, RenderLimits{}, output);
}

Image render(const std::shared_ptr<RenderJob>& j, uint32_t spp, uint64_t& bad) {
  Engine engine;
  RenderLimits limits;
  limits.targetSpp = spp;
  engine.start(j, limits, 2);
  engine.wait();
  bad = engine.progress().badSamples;
  return engine.film().mean(spp);
}

TEST(LightShareOutput, OfferedByMisOnly) {
  int offered = 0;
  for (const IntegratorDesc& d : everyStrategy()) {
    EXPECT_EQ(offersLightShare(d), d.type == IntegratorType::Direct && d.estimator == Estimator::Mis)
        << strategyLabel(d);
    offered += offersLightShare(d);
  }
  EXPECT_EQ(size_t(offered), kLightMeasures.size() * kHeuristics.size());
}

// The split's channels add up to the luminance of the ordinary image (same seed, same sample
// streams: equal up to float rounding), every share is in [0, 1], and both techniques matter somewhere
// (light sampling gives > 90 % of some pixels; with the balance heuristic, cosine directions > 20 % of
// others: the power heuristic leaves them that much only right under the large light).
TEST(LightShareOutput, ChannelsAddUpToTheLuminanceOfTheImage) {
  for (const IntegratorDesc& s : {directByMis(LightMeasure::SolidAngle, MisHeuristic::Balance),
                                  directByMis(LightMeasure::Area, MisHeuristic::Power),
                                  directByMis(LightMeasure::ProjectedSolidAngle, MisHeuristic::Balance),
                                  directByMis(LightMeasure::ProjectedSolidAngle, MisHeuristic::Power)}) {
    SCOPED_TRACE(strategyLabel(s));
    uint64_t badA = 0, badB = 0;
    const Image image = render(job(s, RenderOutput::Radiance), 6, badA);
    const Image split = render(job(s, RenderOutput::MisLightShare), 6, badB);
    EXPECT_EQ(badA + badB, 0u);
    size_t differing = 0, mostlyLight = 0, cosineMatters = 0, noShare = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const float lum = luminance(image.at(x, y));
        const Color3 parts = split.at(x, y);
        const float sum = parts.x + parts.y + parts.z;
        differing += !(std::fabs(sum - lum) <= 1e-5f * std::max(1.f, lum));
        const float share = lightShare(parts);
        if (share < 0.f) {
          ++noShare;
          continue;
        }
        EXPECT_LE(share, 1.f);
        mostlyLight += share > 0.9f;
        cosineMatters += share < 0.8f;
      }
    EXPECT_EQ(differing, 0u);
    EXPECT_GT(mostlyLight, 50u);
    if (s.heuristic == MisHeuristic::Balance) {
      EXPECT_GT(cosineMatters, 10u);
    }
    EXPECT_GT(noShare, 0u);  // the sky
  }
}

// A light-share job of a strategy without that output renders its ordinary image.
TEST(LightShareOutput, OtherStrategiesRenderRadiance) {
  uint64_t bad = 0;
  const Image a = render(job(directByLight(LightMeasure::SolidAngle), RenderOutput::Radiance), 2, bad);
  const Image b = render(job(directByLight(LightMeasure::SolidAngle), RenderOutput::MisLightShare), 2, bad);
  EXPECT_EQ(a.rgb, b.rgb);
}

}  // namespace
}  // namespace penumbra
