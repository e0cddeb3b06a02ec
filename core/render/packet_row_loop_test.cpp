#include "core/render/packet_row_loop.h"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <thread>

#include "core/geometry/procedural_mesh.h"
#include "core/lights/mesh_lights.h"
#include "core/materials/bsdf.h"
#include "core/math/frame.h"
#include "core/render/engine.h"
#include "core/render/filter.h"
#include "core/render/packet_kernels.h"
#include "core/render/packet_scene.h"
#include "core/render/packet_target_test_support.h"
#include "core/render/row_renderer.h"
#include "core/render/strategy_axes.h"
#include "core/sampling/sampler_table.h"

namespace penumbra {
namespace {

using test::ForcedTarget;

struct TestScene {
  std::shared_ptr<const Scene> scene;
  float scale;
};

// Where the test scene's geometry lives: all flat spheres and parallelograms (held by the kernels),
// or with a smooth-shaded mesh among them, as loose triangles or with everything in Embree's BVH (the
// kernels query SceneGeometry).
// The *WithPolygonLights variants add polygon lights: rectangles, which stay flat parallelograms, and
// with the BVH also a glowing rock of triangle lights. The Glossy* variants have glossy materials of every
// model on most surfaces; BvhGlossy also the polygon lights.
enum class Geometry {
  Flat,
  LooseTriangles,
  Bvh,
  FlatWithPolygonLights,
  BvhWithPolygonLights,
  FlatGlossy,
  BvhGlossy
};
bool isGlossy(Geometry g) {
  return g == Geometry::FlatGlossy || g == Geometry::BvhGlossy;
}
bool hasPolygonLights(Geometry g) {
  return g == Geometry::FlatWithPolygonLights || g == Geometry::BvhWithPolygonLights ||
         g == Geometry::BvhGlossy;
}
bool isFlat(Geometry g) {
  return g == Geometry::Flat || g == Geometry::FlatWithPolygonLights || g == Geometry::FlatGlossy;
}
constexpr const char* kGeometryNames[] = {
    "Flat",       "LooseTriangles", "Bvh", "FlatWithPolygonLights", "BvhWithPolygonLights",
    "FlatGlossy", "BvhGlossy"};
const char* geometryName(Geometry g) {
  return kGeometryNames[int(g)];
}

// Every case a lane can meet, all in one image (at coordinates times `scale`): the sky (lanes that miss
// everything), a floor parallelogram and a wall seen from behind (normals flipped to the viewer), a
// diffuse sphere, a black sphere (nothing shaded), a light seen directly that also reflects (albedo
// 0.5, as scene files give emitters) and one that does not, a light of black radiance, a tiny distant
// light, and a diffuse sphere that cuts into a light (shading points inside it, lit by nothing of it);
// unless the geometry is flat, also a rock whose interpolated normals differ from its faces'; with
// polygon lights, a rectangle light overhead facing down (seen from behind by the camera), one on the
// floor facing up, a black one, and unless flat a glowing rock of 20 triangle lights. Without
// sphereLights the spheres that would be lights are left out.
TestScene packetTestScene(float scale, bool deltaLights = false, Geometry geometry = Geometry::Flat,
                          bool sphereLights = true) {
  auto scene = std::make_shared<Scene>();
  auto addObject = [&](Color3 albedo) {
    scene->materials.push_back(SurfaceMaterial{makeDiffuse(albedo)});
    return uint32_t(scene->materials.size() - 1);
  };
  auto addLight = [&](Vec3 c, float r, Color3 radiance, Color3 albedo) {
    if (!sphereLights) return;
    const uint32_t object = addObject(albedo);
    const int32_t index = int32_t(scene->geometry.addSphere(Sphere{c * scale, r * scale}, object));
    scene->materials[object].sphereLight = int32_t(scene->sphereLights.size());
    SphereLight light{Sphere{c * scale, r * scale}, radiance};
    light.geometryIndex = index;
    scene->sphereLights.push_back(light);
  };
  const float s = scale;
  scene->geometry.addMesh(makeGridPlane(Vec3(-4, -1, -4) * s, Vec3(0, 0, 8) * s, Vec3(8, 0, 0) * s, 1, 1),
                          addObject(Color3(0.8f)));
  // A wall whose front faces away from the camera.
  scene->geometry.addMesh(makeGridPlane(Vec3(-3, -1, -2) * s, Vec3(0, 2, 0) * s, Vec3(2, 0, 0) * s, 1, 1),
                          addObject(Color3(0.6f, 0.7f, 0.2f)));
  scene->geometry.addSphere(Sphere{Vec3(0, -0.3f, 0) * s, 0.7f * s}, addObject(Color3(0.5f, 0.25f, 0.9f)));
  scene->geometry.addSphere(Sphere{Vec3(-1.4f, -0.6f, 0.8f) * s, 0.4f * s}, addObject(Color3(0.f)));
  addLight(Vec3(1.2f, 0.9f, 0.6f), 0.3f, Color3(6.f, 5.f, 4.f), Color3(0.5f));
  addLight(Vec3(-0.9f, 1.1f, -0.8f), 0.2f, Color3(3.f, 9.f, 2.f), Color3(0.f));
  addLight(Vec3(0.f, 2.f, 1.f), 0.5f, Color3(0.f), Color3(0.5f));
  addLight(Vec3(40.f, 30.f, 20.f), 1e-3f, Color3(1e6f), Color3(0.5f));
  scene->geometry.addSphere(Sphere{Vec3(1.5f, -0.7f, -0.6f) * s, 0.35f * s}, addObject(Color3(0.9f)));
  addLight(Vec3(1.7f, -0.5f, -0.6f), 0.25f, Color3(2.f), Color3(0.5f));
  if (deltaLights) {
    // A point light above, one at a shading point's place on the floor (no direction there), a black
    // one, and two directional lights (one from below the floor).
    scene->pointLights.push_back(PointLight{Vec3(0.3f, 1.8f, 0.9f) * s, Color3(4.f, 3.f, 2.f)});
    scene->pointLights.push_back(PointLight{Vec3(0.5f, -1.f, 1.2f) * s, Color3(1.f)});
    scene->pointLights.push_back(PointLight{Vec3(-1.f, 1.f, 0.f) * s, Color3(0.f)});
    scene->directionalLights.push_back(DirectionalLight::make(Vec3(-0.4f, 1.f, 0.3f), Color3(0.7f)));
    scene->directionalLights.push_back(DirectionalLight::make(Vec3(0.f, -1.f, 0.2f), Color3(5.f)));
  }
  if (!isFlat(geometry)) {
    TriangleMesh rock = makeRockMesh(geometry == Geometry::LooseTriangles ? 0 : 1, 7);
    for (Vec3& p : rock.positions) p = (p * 0.35f + Vec3(-0.5f, -0.65f, 1.3f)) * s;
    scene->geometry.addMesh(rock, addObject(Color3(0.7f, 0.6f, 0.5f)));
  }
  if (hasPolygonLights(geometry)) {
    auto addMeshLight = [&](const TriangleMesh& mesh, Color3 radiance) {
      const uint32_t object = addObject(Color3(0.5f));
      scene->materials[object].polygonLightsAt = int32_t(scene->polygonLightOfPrim.size());
      addMeshLights(mesh, radiance, scene->polygonLights, scene->polygonLightOfPrim);
      scene->geometry.addMesh(mesh, object);
    };
    addMeshLight(makeGridPlane(Vec3(-1.f, 2.5f, -1.f) * s, Vec3(1.5f, 0, 0) * s, Vec3(0, 0, 1.2f) * s, 1, 1),
                 Color3(4.f, 3.f, 2.f));
    addMeshLight(
        makeGridPlane(Vec3(-2.5f, -0.999f, 0.5f) * s, Vec3(0, 0, 0.8f) * s, Vec3(0.6f, 0, 0) * s, 1, 1),
        Color3(1.f, 2.f, 0.5f));
    addMeshLight(makeGridPlane(Vec3(2.f, -1.f, -1.f) * s, Vec3(0, 1, 0) * s, Vec3(0, 0, 1) * s, 1, 1),
                 Color3(0.f));
    if (!isFlat(geometry)) {
      TriangleMesh glowing = makeRockMesh(0, 3);
      for (Vec3& p : glowing.positions) p = (p * 0.25f + Vec3(-1.6f, -0.7f, -0.5f)) * s;
      addMeshLight(glowing, Color3(0.5f, 1.f, 2.f));
    }
  }
  if (isGlossy(geometry)) {
    // Materials 0-4 are the floor, the wall, the large sphere, the black one (a black conductor reflects
    // nothing) and the light that reflects (a glossy emitter); the other non-emitting surfaces become
    // microfacet too.
    std::vector<SurfaceMaterial>& m = scene->materials;
    m[4].bsdf = makeMicrofacet(Color3(0.2f), 0.3f, 1.5046f, 1.000277f);
    m[0].bsdf = makeRoughConductor(MicrofacetDistribution::Ggx, 0.25f, Color3(0.9f, 0.8f, 0.6f));
    m[1].bsdf = makeMicrofacet(Color3(0.3f, 0.4f, 0.1f), 0.2f, 1.5046f, 1.000277f);
    m[2].bsdf = makeRoughConductor(MicrofacetDistribution::Beckmann, 0.1f, Color3(0.95f));
    m[3].bsdf = makeRoughConductor(MicrofacetDistribution::Ggx, 0.3f, Color3(0.f));
    for (SurfaceMaterial& material : m)
      if (material.sphereLight < 0 && material.polygonLightsAt < 0 && material.bsdf.isDiffuse())
        material.bsdf = makeMicrofacet(material.bsdf.albedo * 0.5f, 0.4f, 1.5046f, 1.000277f);
  }
  buildLightSelections(*scene);
  const AccelMode accel =
      isFlat(geometry) || geometry == Geometry::LooseTriangles ? AccelMode::BruteForce : AccelMode::Embree;
  scene->geometry.build(accel, accel);
  scene->rayLengthBound = scene->geometry.bounds().diagonal() * 1.01f;
  return {std::move(scene), scale};
}

std::shared_ptr<const RenderJob> jobFor(const TestScene& t, const IntegratorDesc& strategy, int samples,
                                        SamplerKind sampler, RenderOutput output = RenderOutput::Radiance) {
  RenderSettings s;
  CameraDesc& cam = s.camera;
  const Vec3 origin = Vec3(2.6f, 1.4f, 3.4f) * t.scale, target = Vec3(0.f, -0.2f, 0.f) * t.scale;
  const Vec3 dir = glm::normalize(target - origin);
  const Vec3 left = glm::normalize(glm::cross(Vec3(0, 1, 0), dir));
  cam.toWorld = cameraToWorld(origin, left, glm::cross(dir, left), dir);
  cam.fovDegrees = 70.f;
  cam.width = 67;  // not a multiple of any packet width
  cam.height = 29;
  s.samplerKind = sampler;
  s.sampleCount = 8;
  s.seed = 5;
  s.integrator = withSamples(strategy, samples);
  s.integrator.lightSamples = samples;     // MIS: `samples` of each light,
  s.integrator.bsdfSamples = samples % 3;  // and 1 or 0 (the light technique alone) of the surface's
  return std::make_shared<RenderJob>(t.scene, s, RenderLimits{}, output);
}

RowRenderer packetRows(const RenderJob& job) {
  return packetRowsFor(job, makeScalarRowRenderer(job));
}

// The film's sums (every pixel's sum and sum of squares, in double) after `spp` passes.
std::vector<double> renderSums(const std::shared_ptr<const RenderJob>& job, bool packets, uint32_t spp) {
  Engine engine;
  engine.setRowRendererFactory(packets ? packetRows : makeScalarRowRenderer);
  engine.start(job, RenderLimits{spp, 0.0}, 2);
  engine.wait();
  EXPECT_EQ(engine.progress().badSamples, 0u);
  return engine.film().sums();
}

// Every strategy a packet kernel computes.
const IntegratorDesc kPacketStrategies[] = {
    directByLight(LightMeasure::Area),
    directByLight(LightMeasure::SolidAngle),
    directByLight(LightMeasure::Area, LightSelection::Uniform),
    directByLight(LightMeasure::SolidAngle, LightSelection::Power),
    directByLight(LightMeasure::Area, LightSelection::Bvh),
    directByLight(LightMeasure::SolidAngle, LightSelection::Bvh),
    directByLight(LightMeasure::ProjectedSolidAngle),
    directByLight(LightMeasure::ProjectedSolidAngle, LightSelection::Bvh),
    directByHemisphere(HemisphereWarp::Uniform),
    directByHemisphere(HemisphereWarp::Cosine),
    directByBsdf(),
    aoBy(HemisphereWarp::Uniform),
    aoBy(HemisphereWarp::Cosine),
    directByMis(LightMeasure::Area, MisHeuristic::Balance),
    directByMis(LightMeasure::Area, MisHeuristic::Power),
    directByMis(LightMeasure::SolidAngle, MisHeuristic::Balance),
    directByMis(LightMeasure::SolidAngle, MisHeuristic::Power),
    directByMis(LightMeasure::ProjectedSolidAngle, MisHeuristic::Balance),
    directByMis(LightMeasure::ProjectedSolidAngle, MisHeuristic::Power),
    integratorOfType(IntegratorType::Simple),
    integratorOfType(IntegratorType::Normals),
};

class PacketRowLoopOn : public testing::TestWithParam<Geometry> {};

// Every instruction set this CPU has; in sanitizer builds (ten times slower) only the widest and the
// narrowest, whose lane counts bound every other's.
std::vector<std::string> targetsToCompare() {
  std::vector<std::string> targets = availablePacketTargets();
#ifdef PENUMBRA_SANITIZED_BUILD
  if (targets.size() > 2) targets = {targets.front(), targets.back()};
#endif
  return targets;
}

// Each lane computes exactly what the scalar integrator computes, so the film is the scalar loop's bit
// for bit: on every instruction set this CPU has, for every strategy with a kernel, every sampler,
// one and several shading samples (MIS: 1 and 3 per light with 1 and 0 of the surface's, and its
// light-share channels at scale 1), with and
// without point and directional lights, at 1e-4, 1 and 1e4 scene units, with the geometry in the
// kernels' flat loops and queried from SceneGeometry, with and without polygon lights (delta lights
// are not repeated there: they add nothing new beside polygon lights), and with glossy materials (with
// the delta lights, whose terms carry f too).
TEST_P(PacketRowLoopOn, EqualsTheScalarLoopBitForBit) {
  const bool polygonLights = hasPolygonLights(GetParam()), glossy = isGlossy(GetParam());
  for (const float scale : {1e-4f, 1.f, 1e4f})
    for (const bool deltaLights : {false, true}) {
      if ((polygonLights || glossy) && deltaLights != glossy) continue;
      const TestScene t = packetTestScene(scale, deltaLights, GetParam());
      ASSERT_EQ(t.scene->polygonLights.empty(), !polygonLights);
      EXPECT_EQ(makePacketScene(*jobFor(t, directByBsdf(), 1, SamplerKind::Independent)).geometryQueried,
                !isFlat(GetParam()));
      for (const std::string& target : targetsToCompare()) {
        ForcedTarget forced(target);
        for (const IntegratorDesc& strategy : kPacketStrategies)
          for (int k = 0; k < kSamplerKindCount; ++k)
            for (const int samples : {1, 3}) {
              const SamplerKind sampler = SamplerKind(k);
              SCOPED_TRACE(target + " " + samplerKindName(sampler) + " samples " + std::to_string(samples) +
                           " " + strategyLabel(strategy) + " scale " + std::to_string(scale) +
                           (deltaLights ? " with point and directional lights" : ""));
              // MIS also as its light-share channels (at one scale: they add no geometry).
              for (const RenderOutput output : {RenderOutput::Radiance, RenderOutput::MisLightShare}) {
                if (output == RenderOutput::MisLightShare && (!offersLightShare(strategy) || scale != 1.f))
                  continue;
                const auto job = jobFor(t, strategy, samples, sampler, output);
                ASSERT_EQ(packetUnsupportedReason(*job), "");
                const std::vector<double> packets = renderSums(job, true, 2),
                                          scalar = renderSums(job, false, 2);
                ASSERT_EQ(packets.size(), scalar.size());
                EXPECT_EQ(packets, scalar) << (output == RenderOutput::MisLightShare ? "light share" : "");
              }
            }
      }
    }
}

INSTANTIATE_TEST_SUITE_P(Geometries, PacketRowLoopOn,
                         testing::Values(Geometry::Flat, Geometry::LooseTriangles, Geometry::Bvh,
                                         Geometry::FlatWithPolygonLights, Geometry::BvhWithPolygonLights,
                                         Geometry::FlatGlossy, Geometry::BvhGlossy),
                         [](const testing::TestParamInfo<Geometry>& info) {
                           return geometryName(info.param);
                         });

// A scene whose only lights are point and directional lights: one light picked per sample by every
// selection (the light BVH empty) picks nothing in lanes as in the scalar loop, on every instruction set.
TEST(PacketRowLoop, PicksNothingWithoutAreaLights) {
  const TestScene t = packetTestScene(1.f, true, Geometry::Flat, false);
  ASSERT_TRUE(t.scene->lightBvh.nodes.empty());
  for (const std::string& target : targetsToCompare()) {
    ForcedTarget forced(target);
    for (const LightSelection selection :
         {LightSelection::Uniform, LightSelection::Power, LightSelection::Bvh})
      for (const LightMeasure measure : {LightMeasure::Area, LightMeasure::SolidAngle}) {
        SCOPED_TRACE(target + " " + strategyLabel(directByLight(measure, selection)));
        const auto job = jobFor(t, directByLight(measure, selection), 1, SamplerKind::Sobol);
        ASSERT_EQ(packetUnsupportedReason(*job), "");
        EXPECT_EQ(renderSums(job, true, 1), renderSums(job, false, 1));
      }
  }
}

// The camera rays and filter weights are computed in lanes: every pixel filter (Mitchell's signed
// lobes take their bin's weight) at its default and at an odd radius, on a camera whose image is
// narrower than a packet and on one wider than high, give the scalar loop's film on every instruction set.
TEST(PacketRowLoop, CameraRaysAndFilterWeightsEqualTheScalarLoopForEveryFilter) {
  const TestScene t = packetTestScene(1.f);
  for (const std::string& target : targetsToCompare()) {
    ForcedTarget forced(target);
    for (const FilterType type :
         {FilterType::Box, FilterType::Tent, FilterType::Gaussian, FilterType::Mitchell})
      for (const float radius : {defaultFilterRadius(type), 1.37f})
        for (const int width : {3, 41}) {
          SCOPED_TRACE(target + " " + filterTypeName(type) + " radius " + std::to_string(radius) + " width " +
                       std::to_string(width));
          auto job = std::make_shared<RenderJob>(
              *jobFor(t, directByLight(LightMeasure::SolidAngle), 1, SamplerKind::ZSobol));
          job->settings.filter.type = type;
          job->settings.filter.radius = radius;
          job->settings.camera.width = width;
          job->settings.camera.height = 11;
          job->settings.camera.fovDegrees = 23.f;
          ASSERT_EQ(packetUnsupportedReason(*job), "");
          EXPECT_EQ(renderSums(job, true, 2), renderSums(job, false, 2));
        }
  }
}

// The image has every kind of lane: sky pixels (0), lights seen directly (brighter than any reflection
// here) and lit surfaces, so the comparison above exercises the masks.
TEST(PacketRowLoop, TheTestImageHasEveryKindOfLane) {
  const auto job =
      jobFor(packetTestScene(1.f), directByLight(LightMeasure::SolidAngle), 1, SamplerKind::Independent);
  const std::vector<double> sums = renderSums(job, true, 1);
  int sky = 0, light = 0, lit = 0;
  for (size_t i = 0; i < sums.size(); i += 6) {
    const double r = sums[i];
    sky += r == 0.0;
    light += r >= 2.0;
    lit += r > 0.0 && r < 2.0;
  }
  EXPECT_GT(sky, 20);
  EXPECT_GT(light, 20);
  EXPECT_GT(lit, 200);
}

// Hundreds of shading draws per camera sample (every light sampled 50 times, MIS 50 times per light
// and twice by the surface, one light picked per sample 150 times) ride in packets and give the
// scalar loop's film bit for bit, with sphere and triangle lights and geometry in Embree, on the
// widest and the narrowest instruction set and every sampler.
TEST(PacketRowLoop, CarriesHundredsOfDrawsPerCameraSample) {
  const TestScene t = packetTestScene(1.f, false, Geometry::BvhWithPolygonLights);
  const std::vector<std::string> targets = availablePacketTargets();
  const IntegratorDesc strategies[] = {directByLight(LightMeasure::Area),
                                       directByLight(LightMeasure::SolidAngle, LightSelection::All),
                                       directByLight(LightMeasure::SolidAngle, LightSelection::Power),
                                       directByMis(LightMeasure::SolidAngle, MisHeuristic::Power)};
  for (const std::string& target : {targets.front(), targets.back()}) {
    ForcedTarget forced(target);
    for (const IntegratorDesc& strategy : strategies)
      for (int k = 0; k < kSamplerKindCount; ++k) {
        const SamplerKind sampler = SamplerKind(k);
        SCOPED_TRACE(target + " " + samplerKindName(sampler) + " " + strategyLabel(strategy));
        auto job = std::make_shared<RenderJob>(*jobFor(t, strategy, 50, sampler));
        if (strategy.lightSelection != LightSelection::All) job->settings.integrator.samples = 150;
        job->settings.integrator.bsdfSamples = 2;
        ASSERT_GT(makePacketScene(*job).drawCount(), 256);
        ASSERT_EQ(packetUnsupportedReason(*job), "");
        EXPECT_EQ(renderSums(job, true, 1), renderSums(job, false, 1));
      }
  }
}

// What the packet path takes, and what it leaves to the scalar loop (with the reason).
TEST(PacketRowLoop, SupportsItsStrategies) {
  const TestScene t = packetTestScene(1.f);
  auto job =
      std::make_shared<RenderJob>(*jobFor(t, directByLight(LightMeasure::Area), 1, SamplerKind::Sobol));
  EXPECT_EQ(packetUnsupportedReason(*job), "");
  job->settings.integrator.lightMeasure = LightMeasure::ProjectedSolidAngle;
  EXPECT_EQ(packetUnsupportedReason(*job), "");
  job->settings.integrator.lightSelection = LightSelection::Bvh;
  EXPECT_EQ(packetUnsupportedReason(*job), "");
  job->settings.integrator.lightMeasure = LightMeasure::Area;
  EXPECT_EQ(packetUnsupportedReason(*job), "");
  job->settings.integrator.samples = kMaxPacketDraws / 2;  // a pick and a light draw each: they fit
  EXPECT_EQ(packetUnsupportedReason(*job), "");
  job->settings.integrator.samples = kMaxPacketDraws / 2 + 1;
  EXPECT_NE(packetUnsupportedReason(*job), "");
  job->settings.integrator.lightSelection = LightSelection::All;
  job->settings.integrator.samples = kMaxPacketDraws;  // 6 lights × kMaxPacketDraws draws do not fit a packet
  EXPECT_NE(packetUnsupportedReason(*job), "");
  job->settings.integrator.samples = 1;
  job->output = RenderOutput::MisLightShare;  // renders radiance for this strategy, as the scalar loop does
  EXPECT_EQ(packetUnsupportedReason(*job), "");
  job->settings.integrator = directByMis(LightMeasure::Area, MisHeuristic::Power);
  EXPECT_EQ(packetUnsupportedReason(*job), "");
  job->settings.integrator = directByLight(LightMeasure::Area);
  job->output = RenderOutput::Radiance;
  // Glossy materials by every strategy.
  auto glossy = std::make_shared<Scene>();
  glossy->geometry.addSphere(Sphere{Vec3(0.f), 1.f}, 0);
  glossy->materials.push_back(SurfaceMaterial{});
  glossy->materials[0].bsdf.type = BsdfType::RoughConductor;
  glossy->geometry.build();
  job = std::make_shared<RenderJob>(glossy, job->settings, RenderLimits{});
  EXPECT_EQ(packetUnsupportedReason(*job), "");
  job->settings.integrator = directByBsdf();
  EXPECT_EQ(packetUnsupportedReason(*job), "");
  job->settings.integrator = directByMis(LightMeasure::Area, MisHeuristic::Power);
  EXPECT_EQ(packetUnsupportedReason(*job), "");
  // Ambient occlusion sees only the geometry.
  job->settings.integrator = withSamples(aoBy(HemisphereWarp::Cosine), 4);
  EXPECT_EQ(packetUnsupportedReason(*job), "");
  job->settings.integrator = directByMis(LightMeasure::ProjectedSolidAngle, MisHeuristic::Power);
  EXPECT_EQ(packetUnsupportedReason(*job), "");
}

// Every direct strategy takes packets in every scene kind, rays queried or flat,
// with sphere or polygon lights: polygons by the projected solid angle too, whose map is set up and
// sampled in lanes (the row loop says so).
TEST(PacketRowLoop, TakesPacketsForEveryStrategyWithPolygonLights) {
  const TestScene queried = packetTestScene(1.f, false, Geometry::BvhWithPolygonLights);
  const TestScene flat = packetTestScene(1.f, false, Geometry::FlatWithPolygonLights);
  const TestScene spheres = packetTestScene(1.f, false, Geometry::Bvh);
  std::vector<IntegratorDesc> strategies = {directByHemisphere(HemisphereWarp::Cosine)};
  for (const LightMeasure measure :
       {LightMeasure::Area, LightMeasure::SolidAngle, LightMeasure::ProjectedSolidAngle}) {
    for (const LightSelection selection : {LightSelection::All, LightSelection::Power, LightSelection::Bvh})
      strategies.push_back(directByLight(measure, selection));
    strategies.push_back(directByMis(measure, MisHeuristic::Power));
  }
  for (const TestScene* t : {&queried, &flat, &spheres})
    for (const IntegratorDesc& d : strategies) {
      const auto job = jobFor(*t, d, 1, SamplerKind::Sobol);
      SCOPED_TRACE(strategyLabel(d));
      EXPECT_EQ(packetUnsupportedReason(*job), "");
      if (packetPathEnabled()) {
        EXPECT_EQ(rowLoopSummary(*job).rfind("packets of ", 0), 0u) << rowLoopSummary(*job);
      }
    }
}

// Every instruction set this binary has kernels for runs here and can be chosen; an unknown name
// cannot.
TEST(PacketRowLoop, InstructionSetsCanBeChosen) {
  const std::vector<std::string> targets = availablePacketTargets();
  ASSERT_FALSE(targets.empty());
  for (const std::string& target : targets) {
    ForcedTarget forced(target);
    EXPECT_EQ(packetTargetName(), target);
    EXPECT_GE(packetLanes(), 1);
    EXPECT_LE(packetLanes(), kMaxPacketLanes);
  }
  EXPECT_FALSE(forcePacketTarget("NEON"));
  EXPECT_EQ(packetTargetName(), targets.front());
}

// Cancelling stops a row between packets: a cancelled 1-spp render of a 16384 x 64 image (about a
// second of work) ends at once with no pass completed.
TEST(PacketRowLoop, CancelStopsBetweenPackets) {
  auto job = std::make_shared<RenderJob>(
      *jobFor(packetTestScene(1.f), directByLight(LightMeasure::Area), 8, SamplerKind::Independent));
  job->settings.camera.width = 16384;
  job->settings.camera.height = 64;
  Engine engine;
  engine.setRowRendererFactory(packetRows);
  engine.start(job, RenderLimits{1, 0.0}, 1);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const auto start = std::chrono::steady_clock::now();
  engine.cancel();
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  EXPECT_EQ(engine.progress().spp, 0u);
  EXPECT_TRUE(engine.progress().finished);
}

}  // namespace
}  // namespace penumbra
