// Polygon lights as the integrators use them. One light sample per iteration, set-up included (the
// technique is built once per shading point and light): a triangle and a quad light above a floor by
// each measure, beside the sphere light of the same size and place. And the cost of one camera sample
// of direct/solid-angle with the light BVH as the count of emitting triangles grows from 10 to 10,000.
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <vector>

#include "core/geometry/procedural_mesh.h"
#include "core/integrators/direct_integrator.h"
#include "core/lights/mesh_lights.h"
#include "core/sampling/sampler.h"
#include "core/world/scene.h"

namespace penumbra {
namespace {

constexpr int kPoints = 1 << 10;

// The floor z = 0 with shading points on it, and one light 1.75 above: a sphere of radius 0.1, a
// triangle or a square 0.2 across (as bright).
struct LightFixture {
  Scene scene;
  std::vector<ShadingPoint> points;
  std::vector<Vec2> u;
  SphereLight sphere{Sphere{Vec3(0.1f, -0.2f, 1.75f), 0.1f}, Color3(1)};
  PolygonLight triangle =
      PolygonLight::make(Vec3(0, -0.3f, 1.75f), Vec3(0, 0.2f, 0), Vec3(0.2f, 0, 0), false, Color3(1));
  PolygonLight quad =
      PolygonLight::make(Vec3(0, -0.3f, 1.75f), Vec3(0, 0.2f, 0), Vec3(0.2f, 0, 0), true, Color3(1));

  LightFixture() {
    scene.geometry.addMesh(makeGridPlane(Vec3(-4, -4, 0), Vec3(8, 0, 0), Vec3(0, 8, 0), 1, 1), 0);
    scene.materials.push_back(SurfaceMaterial{makeDiffuse(Color3(1.f))});
    scene.geometry.build();
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> d(0.f, 0.999f);
    for (int i = 0; i < kPoints; ++i) {
      Ray ray;
      ray.o = Vec3(2 * d(rng) - 1, 2 * d(rng) - 1, 1.f);
      ray.d = Vec3(0, 0, -1);
      SurfaceHit hit;
      scene.geometry.intersect(ray, hit);
      points.emplace_back(scene, ray, hit);
      u.push_back(Vec2(d(rng), d(rng)));
    }
  }
};

template <LightMeasure kMeasure, class Light>
void sampleLight(benchmark::State& state, const Light& light, const LightFixture& f) {
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ & (kPoints - 1);
    const LightTechnique<kMeasure, Light> technique(light, f.points[k]);
    benchmark::DoNotOptimize(technique.sample(f.u[k]));
  }
  state.SetItemsProcessed(state.iterations());
}

// Arg: 0 sphere, 1 triangle, 2 quad.
template <LightMeasure kMeasure>
void BM_LightSample(benchmark::State& state) {
  static const LightFixture f;
  if (state.range(0) == 0) sampleLight<kMeasure>(state, f.sphere, f);
  if (state.range(0) == 1) sampleLight<kMeasure>(state, f.triangle, f);
  if (state.range(0) == 2) sampleLight<kMeasure>(state, f.quad, f);
}
BENCHMARK(BM_LightSample<LightMeasure::Area>)->Name("BM_LightSample_Area")->DenseRange(0, 2);
BENCHMARK(BM_LightSample<LightMeasure::SolidAngle>)->Name("BM_LightSample_SolidAngle")->DenseRange(0, 2);
BENCHMARK(BM_LightSample<LightMeasure::ProjectedSolidAngle>)
    ->Name("BM_LightSample_ProjectedSolidAngle")
    ->DenseRange(0, 2);

// A floor under n small separate emitting triangles scattered over a ceiling 3 above it, facing down.
std::unique_ptr<Scene> manyTrianglesScene(int n) {
  auto scene = std::make_unique<Scene>();
  scene->geometry.addMesh(makeGridPlane(Vec3(-10, -10, 0), Vec3(20, 0, 0), Vec3(0, 20, 0), 1, 1), 0);
  scene->materials.push_back(SurfaceMaterial{makeDiffuse(Color3(1.f))});
  TriangleMesh mesh;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> d(-8.f, 8.f);
  const float size = 0.5f / std::sqrt(float(n) / 10.f);  // the same total area at every n
  for (int i = 0; i < n; ++i) {
    const Vec3 c(d(rng), d(rng), 3.f);
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {c, c + Vec3(0, size, 0), c + Vec3(size, 0, 0)});
    mesh.triangles.push_back(glm::uvec3(base, base + 1, base + 2));
  }
  SurfaceMaterial emitter;
  emitter.bsdf = makeDiffuse(Color3(0.f));
  emitter.polygonLightsAt = 0;
  addMeshLights(mesh, Color3(4.f), scene->polygonLights, scene->polygonLightOfPrim);
  scene->geometry.addMesh(mesh, 1);
  scene->materials.push_back(emitter);
  scene->geometry.build();
  buildLightSelections(*scene);
  scene->rayLengthBound = scene->geometry.bounds().diagonal() * 1.01f;
  return scene;
}

// One camera sample (a ray down onto the floor, one light sample) of direct/solid-angle-bvh.
void BM_ManyTriangleLights_CameraSample(benchmark::State& state) {
  const auto scene = manyTrianglesScene(int(state.range(0)));
  const LightDirectIntegrator<LightMeasure::SolidAngle, LightSelection::Bvh> integrator{1};
  Sampler sampler(SamplerKind::Independent, 1, 3);
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> d(-6.f, 6.f);
  std::vector<Ray> rays(kPoints);
  for (Ray& r : rays) {
    r.o = Vec3(d(rng), d(rng), 1.f);
    r.d = Vec3(0, 0, -1);
  }
  uint32_t i = 0;
  for (auto _ : state) {
    sampler.startPixelSample(IVec2(int(i & 63), int(i >> 6)), 0);
    benchmark::DoNotOptimize(integrator.Li(*scene, rays[i & (kPoints - 1)], sampler));
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ManyTriangleLights_CameraSample)->Arg(10)->Arg(100)->Arg(1000)->Arg(10000);

}  // namespace
}  // namespace penumbra
