// The closed forms through the packet path: whole images rendered by the engine (camera samples in
// SIMD lanes), each pixel's mean against the closed form at the point its centre sees, within five of
// the film's standard errors; on every instruction set this CPU has, for every strategy with a packet
// kernel and every sampler.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/analysis/closed_forms.h"
#include "core/lights/polygon_lambert.h"
#include "core/materials/bsdf_albedo.h"
#include "core/math/frame.h"
#include "core/render/camera.h"
#include "core/render/engine.h"
#include "core/render/packet_kernels.h"
#include "core/render/packet_row_loop.h"
#include "core/render/packet_scene.h"
#include "core/render/strategy_axes.h"
#include "core/sampling/sampler_table.h"
#include "core/scene/scene_builder.h"

namespace penumbra {
namespace {

constexpr int kSize = 8;
constexpr uint32_t kSpp = 64;
constexpr Vec3 kCameraOrigin(0.4f, -0.3f, 3.f);

// A sphere of the test scenes: an emitter of radiance Le or (Le = 0) a diffuse occluder.
struct SphereDesc {
  Vec3 c;
  float r, Le;
};

// The plane z = 0 (albedo 1, half-size 10) under spheres; a camera 3 units above looking straight down
// with a 2° field of view, so each pixel's footprint is ~0.01 units and the closed form at its centre
// is its expectation to ~1e-5.
// A rectangle light facing down onto the plane: centre c, half-sizes hx, hy, radiance Le.
struct RectangleDesc {
  Vec3 c;
  float hx, hy, Le;
};

// The plane's BSDF, as the scene file gives it.
constexpr const char* kWhiteDiffuse = "<bsdf type=\"diffuse\"><color name=\"albedo\" value=\"1\"/></bsdf>";

LoadedScene planeScene(const std::vector<SphereDesc>& spheres,
                       const std::vector<RectangleDesc>& rectangles = {},
                       const std::string& planeBsdf = kWhiteDiffuse) {
  std::ostringstream xml;
  xml.precision(9);
  xml << "<scene><integrator type=\"direct\"/>"
      << "<shape type=\"plane\">" << planeBsdf
      << "<transform name=\"toWorld\"><scale value=\"10,1,10\"/><rotate axis=\"1,0,0\" angle=\"90\"/>"
      << "</transform></shape>";
  for (const SphereDesc& sphere : spheres) {
    xml << "<shape type=\"sphere\"><point name=\"center\" value=\"" << sphere.c.x << "," << sphere.c.y << ","
        << sphere.c.z << "\"/><float name=\"radius\" value=\"" << sphere.r << "\"/>";
    if (sphere.Le > 0.f)
      xml << "<emitter type=\"area\"><color name=\"radiance\" value=\"" << sphere.Le << "\"/></emitter>";
    xml << "</shape>";
  }
  for (const RectangleDesc& r : rectangles)  // y mirrored and z flipped: the rectangle faces −z
    xml << "<shape type=\"rectangle\"><transform name=\"toWorld\"><matrix value=\"" << r.hx << " 0 0 "
        << r.c.x << " 0 " << -r.hy << " 0 " << r.c.y << " 0 0 -1 " << r.c.z << " 0 0 0 1\"/></transform>"
        << "<emitter type=\"area\"><color name=\"radiance\" value=\"" << r.Le << "\"/></emitter></shape>";
  xml << "</scene>";
  LoadedScene s = loadSceneFromString(xml.str(), "packet-closed-form.xml", ".");
  CameraDesc& cam = s.settings.camera;
  const Vec3 origin = kCameraOrigin, dir(0.f, 0.f, -1.f), left(-1.f, 0.f, 0.f);
  cam.toWorld = cameraToWorld(origin, left, glm::cross(dir, left), dir);
  cam.fovDegrees = 2.f;
  cam.width = cam.height = kSize;
  return s;
}

// Every pixel of the packet path's image of `strategy` (`samples` shading samples per camera sample)
// against truth(x) at the plane point x its centre sees.
template <class Truth>
void expectClosedForm(const LoadedScene& s, const IntegratorDesc& strategy, const Truth& truth,
                      int samples = 2) {
  for (const std::string& target : availablePacketTargets()) {
    ASSERT_TRUE(forcePacketTarget(target));
    for (const SamplerRow& row : samplerTable()) {
      SCOPED_TRACE(target + " " + strategyLabel(strategy) + " " + std::string(row.label));
      RenderSettings settings = s.settings;
      settings.integrator = withSamples(strategy, samples);
      settings.integrator.lightSamples = settings.integrator.bsdfSamples = 2;
      settings.samplerKind = row.kind;
      settings.seed = 3;
      auto job = std::make_shared<const RenderJob>(s.scene, settings, RenderLimits{kSpp, 0.0});
      ASSERT_EQ(packetUnsupportedReason(*job), "");
      Engine engine;
      engine.setRowRendererFactory(
          [](const RenderJob& j) { return packetRowsFor(j, makeScalarRowRenderer(j)); });
      engine.start(job, RenderLimits{kSpp, 0.0}, 2);
      engine.wait();
      EXPECT_EQ(engine.progress().badSamples, 0u);
      const PerspectiveCamera camera(settings.camera);
      // Each pixel, and the image's sum (a bias too small for one pixel's bound shows in the sum of all;
      // pixels' errors are independent or, sharing nets, anti-correlated, so the bound is conservative).
      double error = 0.0, variance = 0.0, total = 0.0;
      for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
          const Ray ray = camera.generateRay(Vec2(float(x) + 0.5f, float(y) + 0.5f));
          const Vec3 p = ray.o + (-ray.o.z / ray.d.z) * ray.d;
          const double expected = truth(glm::dvec3(p));
          Color3 mean, se;
          engine.film().pixelStatistics(kSpp, x, y, mean, se);
          EXPECT_NEAR(mean.y, expected, 5.0 * se.y + 1e-4 * expected) << "pixel " << x << "," << y;
          error += double(mean.y) - expected;
          variance += double(se.y) * double(se.y);
          total += expected;
        }
      EXPECT_LE(std::abs(error), 5.0 * std::sqrt(variance) + 1e-4 * total) << "the image's sum";
    }
  }
  forcePacketTarget("auto");
}

// Direct light from a sphere light fully above the plane: L = (albedo/π) Le I(θ, α).
TEST(PacketClosedForm, ThePlaneUnderASphereLightForEveryDirectKernel) {
  const Vec3 c(0.9f, -0.2f, 1.1f);
  const float r = 0.35f, Le = 20.f;
  const LoadedScene s = planeScene({{c, r, Le}});
  auto truth = [&](const glm::dvec3& x) {
    return double(Le) / kPiD * sphereLightIrradianceFactor(x, glm::dvec3(0, 0, 1), glm::dvec3(c), double(r));
  };
  for (const IntegratorDesc& strategy :
       {directByLight(LightMeasure::Area), directByLight(LightMeasure::SolidAngle),
        directByHemisphere(HemisphereWarp::Uniform), directByHemisphere(HemisphereWarp::Cosine),
        directByBsdf(), directByMis(LightMeasure::Area, MisHeuristic::Balance),
        directByMis(LightMeasure::Area, MisHeuristic::Power),
        directByMis(LightMeasure::SolidAngle, MisHeuristic::Balance),
        directByMis(LightMeasure::SolidAngle, MisHeuristic::Power)})
    expectClosedForm(s, strategy, truth);
}

// Sets an environment variable for the life of the object.
struct ScopedEnvironment {
  ScopedEnvironment(const char* name, const char* value) : name(name) { setenv(name, value, 1); }
  ~ScopedEnvironment() { unsetenv(name); }
  const char* name;
};

// Two sphere lights above the plane: the sum of their closed forms, by light sampling of every light
// and of one light picked per sample by each selection (whose pmfs then matter); with the spheres in
// the flat loops and in Embree's BVH (the kernels then query SceneGeometry for every ray).
TEST(PacketClosedForm, ThePlaneUnderTwoSphereLightsForEveryLightSelection) {
  const std::vector<SphereDesc> lights = {{Vec3(0.9f, -0.2f, 1.1f), 0.35f, 20.f},
                                          {Vec3(-0.4f, 0.5f, 0.7f), 0.2f, 35.f}};
  auto truth = [&](const glm::dvec3& x) {
    double L = 0.0;
    for (const SphereDesc& l : lights)
      L += double(l.Le) / kPiD *
           sphereLightIrradianceFactor(x, glm::dvec3(0, 0, 1), glm::dvec3(l.c), double(l.r));
    return L;
  };
  for (const char* accel : {"brute-force", "bvh"}) {
    SCOPED_TRACE(std::string("spheres by ") + accel);
    const ScopedEnvironment env("PENUMBRA_SPHERE_ACCEL", accel);
    const LoadedScene s = planeScene(lights);
    ASSERT_EQ(s.scene->geometry.spheresUseBvh(), std::string(accel) == "bvh");
    for (const LightMeasure measure : {LightMeasure::Area, LightMeasure::SolidAngle})
      for (const LightSelection selection :
           {LightSelection::All, LightSelection::Uniform, LightSelection::Power, LightSelection::Bvh})
        expectClosedForm(s, directByLight(measure, selection), truth);
  }
}

// A rectangle light and a sphere light above the plane: Lambert's closed form for the rectangle plus the
// sphere's, by every light measure and selection, MIS of each measure, and by the hemisphere (whose
// directions must find the rectangle's emission); with the shapes in the flat loops and with the sphere in
// Embree's BVH (every ray then queried, and the rectangle no longer a flat parallelogram of the kernels).
TEST(PacketClosedForm, ThePlaneUnderARectangleAndASphereLight) {
  // The rectangle close beside the camera's view, the sphere further off (no shadow ray to it meets the
  // rectangle).
  const SphereDesc sphere{Vec3(-0.6f, 0.5f, 0.7f), 0.25f, 20.f};
  const RectangleDesc rectangle{Vec3(0.5f, 0.25f, 0.6f), 0.4f, 0.2f, 10.f};
  for (const char* accel : {"brute-force", "bvh"}) {
    SCOPED_TRACE(std::string("spheres by ") + accel);
    const ScopedEnvironment env("PENUMBRA_SPHERE_ACCEL", accel);
    const LoadedScene s = planeScene({sphere}, {rectangle});
    ASSERT_EQ(s.scene->polygonLights.size(), 1u);
    ASSERT_EQ(makePacketScene(RenderJob(s.scene, s.settings, RenderLimits{})).geometryQueried,
              std::string(accel) == "bvh");
    const PolygonLight& light = s.scene->polygonLights[0];
    ASSERT_LT(light.n.z, -0.99f);  // facing the plane
    auto truth = [&](const glm::dvec3& x) {
      const glm::dvec3 up(0, 0, 1);
      return double(sphere.Le) / kPiD *
                 sphereLightIrradianceFactor(x, up, glm::dvec3(sphere.c), double(sphere.r)) +
             double(rectangle.Le) / kPiD * polygonLightIrradianceFactor(light, x, up);
    };
    for (const LightMeasure measure :
         {LightMeasure::Area, LightMeasure::SolidAngle, LightMeasure::ProjectedSolidAngle})
      for (const LightSelection selection : {LightSelection::All, LightSelection::Power, LightSelection::Bvh})
        expectClosedForm(s, directByLight(measure, selection), truth);
    for (const IntegratorDesc& strategy :
         {directByMis(LightMeasure::Area, MisHeuristic::Balance),
          directByMis(LightMeasure::SolidAngle, MisHeuristic::Power),
          directByMis(LightMeasure::ProjectedSolidAngle, MisHeuristic::Power)})
      expectClosedForm(s, strategy, truth);
    // Hemisphere directions find the small sphere with probability ~0.03: 16 per camera sample make a
    // pixel without a hit (whose standard error then misses the sphere's part) vanishingly rare.
    for (const IntegratorDesc& strategy : {directByHemisphere(HemisphereWarp::Uniform),
                                           directByHemisphere(HemisphereWarp::Cosine), directByBsdf()})
      expectClosedForm(s, strategy, truth, 16);
  }
}

// A glossy plane (each model) under a sphere light beside the mirror direction of the view, so that the
// pixels see the highlight's flank: L = Le ∫ f(wo, wi) cos θi dωi over the light's cone (coneReflectance's
// quadrature, no closed form), by every direct strategy: its BSDF evaluated and sampled lane by lane.
TEST(PacketClosedForm, AGlossyPlaneUnderASphereLightForEveryDirectKernel) {
  const Vec3 c(0.4f, 0.45f, 1.6f);
  const float r = 0.3f, Le = 20.f;
  const char* bsdfs[] = {
      "<bsdf type=\"microfacet\"><float name=\"alpha\" value=\"0.2\"/><color name=\"kd\" "
      "value=\"0.3\"/></bsdf>",
      "<bsdf type=\"roughconductor\"><string name=\"distribution\" value=\"ggx\"/>"
      "<float name=\"alpha\" value=\"0.3\"/></bsdf>",
      "<bsdf type=\"roughconductor\"><string name=\"distribution\" value=\"beckmann\"/>"
      "<float name=\"alpha\" value=\"0.25\"/></bsdf>"};
  for (const char* bsdf : bsdfs) {
    SCOPED_TRACE(bsdf);
    const LoadedScene s = planeScene({{c, r, Le}}, {}, bsdf);
    const Bsdf& plane = s.scene->materials[0].bsdf;
    ASSERT_FALSE(plane.isDiffuse());
    // The pixels' truths, once each (the quadrature is the slow part).
    std::map<std::pair<double, double>, double> truths;
    auto truth = [&](const glm::dvec3& x) {
      double& L = truths[{x.x, x.y}];
      if (L == 0.0) {
        const glm::dvec3 toLight = glm::dvec3(c) - x;
        const double d = glm::length(toLight), sinMax = double(r) / d;
        // The plane's normal is +z and its shading frame the world's (Frame(+z)).
        const Vec3 wo = glm::normalize(kCameraOrigin - Vec3(x));
        L = double(Le) * coneReflectance(plane, wo, toLight / d, std::sqrt(1 - sinMax * sinMax), 400);
      }
      return L;
    };
    for (const IntegratorDesc& strategy :
         {directByLight(LightMeasure::Area), directByLight(LightMeasure::SolidAngle),
          directByLight(LightMeasure::ProjectedSolidAngle),
          directByLight(LightMeasure::SolidAngle, LightSelection::Bvh),
          directByLight(LightMeasure::Area, LightSelection::Power),
          directByMis(LightMeasure::Area, MisHeuristic::Balance),
          directByMis(LightMeasure::SolidAngle, MisHeuristic::Power),
          directByMis(LightMeasure::ProjectedSolidAngle, MisHeuristic::Balance)})
      expectClosedForm(s, strategy, truth);
    // Directions of the hemisphere (~2 %) and of the BSDF (~5 % on the flank of the highlight) find the
    // light rarely: 16 per camera sample make a pixel without a hit (whose standard error then misses
    // the light's part) vanishingly rare, as above.
    for (const IntegratorDesc& strategy : {directByHemisphere(HemisphereWarp::Uniform),
                                           directByHemisphere(HemisphereWarp::Cosine), directByBsdf()})
      expectClosedForm(s, strategy, truth, 16);
  }
}

// Ambient occlusion of the plane beside a sphere floating above it: 1 − I(θ, α)/π.
TEST(PacketClosedForm, ThePlaneBesideAnOccludingSphereForBothAoKernels) {
  const Vec3 c(0.8f, -0.1f, 0.5f);
  const float r = 0.3f;
  const LoadedScene s = planeScene({{c, r, 0.f}});
  auto truth = [&](const glm::dvec3& x) {
    return aoPlaneWithSphere(x, glm::dvec3(0, 0, 1), glm::dvec3(c), r);
  };
  for (const IntegratorDesc& strategy : {aoBy(HemisphereWarp::Uniform), aoBy(HemisphereWarp::Cosine)})
    expectClosedForm(s, strategy, truth);
}

}  // namespace
}  // namespace penumbra
