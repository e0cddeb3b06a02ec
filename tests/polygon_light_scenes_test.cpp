// Polygon and mesh lights end to end: the Cornell box and the glowing-rock scene render with every
// light measure, MIS with each, hemisphere sampling and every light selection, without a bad sample and
// with one mean image (within noise); an emitter seen from behind is its diffuse surface.
#include <gtest/gtest.h>

#include <cmath>

#include "core/render/engine.h"
#include "core/render/strategy_axes.h"
#include "core/render/strategy_dispatch.h"
#include "core/scene/scene_builder.h"
#include "tests/test_support.h"

namespace penumbra {
namespace {

using Sets = std::vector<std::pair<std::string, std::string>>;

struct Rendered {
  double mean = 0, standardError = 0;  // over all pixels and channels
  uint64_t bad = 0;
};

Rendered render(const std::string& scene, Sets sets, uint32_t spp) {
  sets.push_back({"camera.width", "40"});
  sets.push_back({"camera.height", "40"});
  const LoadedScene s = loadScene(test::sourcePath(scene), sets);
  const RenderLimits limits{spp, 0.0};
  Engine engine;
  engine.start(std::make_shared<const RenderJob>(s.scene, s.settings, limits), limits);
  engine.wait();
  const Image mean = engine.film().mean(spp), se = engine.film().standardError(spp);
  Rendered r;
  double var = 0;
  for (size_t i = 0; i < mean.rgb.size(); ++i) {
    r.mean += mean.rgb[i];
    var += double(se.rgb[i]) * se.rgb[i];
  }
  r.mean /= double(mean.rgb.size());
  r.standardError = std::sqrt(var) / double(mean.rgb.size());
  r.bad = engine.progress().badSamples;
  return r;
}

// Each strategy's mean image against projected solid angle's (the least noisy), within 4.5 combined
// standard errors.
void expectOneMeanForEveryStrategy(const std::string& scene, const std::vector<Sets>& strategies,
                                   uint32_t spp) {
  const Rendered reference = render(scene, {{"integrator.measure", "projected-solid-angle"}}, spp);
  ASSERT_EQ(reference.bad, 0u);
  ASSERT_GT(reference.mean, 0.0);
  for (const Sets& sets : strategies) {
    std::string label;
    for (const auto& [k, v] : sets) label += k + "=" + v + " ";
    const Rendered r = render(scene, sets, spp);
    EXPECT_EQ(r.bad, 0u) << scene << " " << label;
    const double bound = 4.5 * std::hypot(r.standardError, reference.standardError);
    EXPECT_NEAR(r.mean, reference.mean, bound) << scene << " " << label;
  }
}

std::vector<Sets> everyDirectStrategy() {
  std::vector<Sets> out;
  for (const char* measure : {"area", "solid-angle", "projected-solid-angle"}) {
    out.push_back({{"integrator.measure", measure}});
    out.push_back({{"integrator.measure", "mis"}, {"integrator.lightMeasure", measure}});
  }
  out.push_back({{"integrator.measure", "hemisphere"}, {"integrator.warp-type", "cosine-hemisphere"}});
  return out;
}

TEST(PolygonLightScenes, TheCornellBoxHasOneImageWhateverTheStrategy) {
  std::vector<Sets> strategies = everyDirectStrategy();
  for (const char* sampler : {"independent", "stratified", "sobol"})
    strategies.push_back({{"integrator.measure", "solid-angle"}, {"sampler.type", sampler}});
  expectOneMeanForEveryStrategy("scenes/cornell-box/cornell-box.xml", strategies, 16);
}

TEST(PolygonLightScenes, TheGlowingRockHasOneImageWhateverTheLightSelection) {
  std::vector<Sets> strategies = everyDirectStrategy();
  for (const char* selection : {"all", "uniform", "power", "bvh"})
    for (const char* measure : {"area", "solid-angle", "projected-solid-angle"})
      strategies.push_back({{"integrator.measure", measure}, {"integrator.lightSelection", selection}});
  expectOneMeanForEveryStrategy("scenes/mesh-light/glowing-rock.xml", strategies, 8);
}

// A rectangle light facing down, a point light above it, seen from above: the back of the light
// reflects the point light like any diffuse surface (the default albedo 0.5) and emits nothing; seen
// from below it is its radiance (and reflects nothing: the point light is behind it).
TEST(PolygonLightScenes, AnEmitterSeenFromBehindIsItsDiffuseSurface) {
  const std::string scene = R"(<scene>
    <integrator type="direct"><string name="measure" value="solid-angle"/></integrator>
    <sampler type="independent"><integer name="sampleCount" value="1"/></sampler>
    <camera type="perspective"><float name="fov" value="10"/>
      <integer name="width" value="8"/><integer name="height" value="8"/>
      <transform name="toWorld"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform></camera>
    <shape type="rectangle"><transform name="toWorld"><rotate axis="1, 0, 0" angle="180"/>
      <translate value="0, 0, 2"/></transform>
      <emitter type="area"><color name="radiance" value="7"/></emitter></shape>
    <emitter type="point"><point name="position" value="0, 0, 3"/><color name="power" value="4"/></emitter>
  </scene>)";
  const LoadedScene s = loadSceneFromString(scene, "behind.xml", ".");
  for (bool fromAbove : {true, false}) {
    Ray ray;
    ray.o = Vec3(0.01f, 0.02f, fromAbove ? 5.f : -5.f);
    ray.d = Vec3(0, 0, fromAbove ? -1.f : 1.f);
    // Light sampling of the light itself adds nothing at a point in its plane: no variance.
    const RayEstimate e = estimateRayOf(s.settings.integrator, *s.scene, ray, 64, 1);
    // The point light is 1 above and (0.01, 0.02) aside of the hit: I cos θ / d².
    const double d2 = 1.0 + 0.01 * 0.01 + 0.02 * 0.02;
    const double expected = fromAbove ? 0.5 / kPiD * 4.0 / (d2 * std::sqrt(d2)) : 7.0;
    EXPECT_EQ(e.bad, 0u);
    EXPECT_NEAR(e.mean, expected, 1e-5 * expected) << (fromAbove ? "from above" : "from below");
    EXPECT_EQ(e.standardError, 0.0);
  }
}

}  // namespace
}  // namespace penumbra
