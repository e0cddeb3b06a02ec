// Ray throughput of SceneGeometry, single thread. Run: build/penumbra_bench --benchmark_filter=...
// items_per_second is rays/s.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <random>
#include <vector>

#include "core/geometry/procedural_mesh.h"
#include "core/geometry/scene_geometry.h"
#include "core/math/float_util.h"
#include "core/sampling/random_unit.h"

namespace penumbra {
namespace {

constexpr int kRayCount = 1 << 14;

// The sphere-area scene (scenes/hw2/Tests): a unit sphere on a 200×200 two-triangle plane, a small sphere
// light.
SceneGeometry twoSpheresAndPlane(AccelMode mode = AccelMode::Auto) {
  SceneGeometry g;
  g.addSphere(Sphere{Vec3(1, -1.5f, 1.75f), 0.1f}, 0);
  g.addSphere(Sphere{Vec3(0), 1.f}, 1);
  g.addMesh(makeGridPlane(Vec3(-100, -100, -1), Vec3(200, 0, 0), Vec3(0, 200, 0), 1, 1), 2);
  g.build(mode);
  return g;
}

// Camera rays from (4, 4, 0) into a 40° cone around the origin.
std::vector<Ray> cameraRays() {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  std::vector<Ray> rays(kRayCount);
  const Vec3 eye(4, 4, 0);
  for (Ray& r : rays) r = Ray{eye, glm::normalize(Vec3(u(rng), u(rng), u(rng)) * 1.5f - eye)};
  return rays;
}

// Arg: 0 = Auto (brute force for this scene), 2 = Embree for the plane.
void BM_TwoSpheresPlane_Intersect(benchmark::State& state) {
  SceneGeometry g = twoSpheresAndPlane(static_cast<AccelMode>(state.range(0)));
  std::vector<Ray> rays = cameraRays();
  size_t i = 0;
  for (auto _ : state) {
    SurfaceHit hit;
    benchmark::DoNotOptimize(g.intersect(rays[i++ & (kRayCount - 1)], hit));
    benchmark::DoNotOptimize(hit);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_TwoSpheresPlane_Intersect)->Arg(0)->Arg(2);

void BM_TwoSpheresPlane_Occluded(benchmark::State& state) {
  SceneGeometry g = twoSpheresAndPlane(static_cast<AccelMode>(state.range(0)));
  // Shadow rays from visible surface points towards random points on the light.
  std::vector<Ray> cam = cameraRays(), rays;
  std::mt19937 rng(2);
  for (const Ray& c : cam) {
    SurfaceHit hit;
    if (!g.intersect(c, hit) || hit.objectId == 0) continue;
    Vec3 target = Vec3(1, -1.5f, 1.75f) + 0.1f * randomUnit(rng);
    Vec3 o = offsetRayOrigin(hit.p, hit.ng, hit.offsetScale, target - hit.p);
    Vec3 d = target - o;
    float len = glm::length(d);
    rays.push_back(Ray{o, d / len, 0.f, len * (1.f - 1e-4f)});
  }
  const size_t n = rays.size();
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(g.occluded(rays[i]));
    if (++i == n) i = 0;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_TwoSpheresPlane_Occluded)->Arg(0)->Arg(2);

// ---- Brute force vs Embree on small triangle soups (justifies kBruteForceMaxTriangles) ----------
TriangleMesh triangleSoup(int n) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  TriangleMesh m;
  for (int i = 0; i < n; ++i) {
    Vec3 c(u(rng), u(rng), u(rng));
    for (int k = 0; k < 3; ++k) m.positions.push_back(c + 0.3f * Vec3(u(rng), u(rng), u(rng)));
    m.triangles.push_back({3 * i, 3 * i + 1, 3 * i + 2});
  }
  return m;
}

// Nearest-hit queries of rays from a sphere of radius `from` towards points in [-1, 1]^3.
void intersectBench(benchmark::State& state, const SceneGeometry& g, float from = 3.f, unsigned seed = 4) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  std::vector<Ray> rays(kRayCount);
  for (Ray& r : rays) {
    r.o = randomUnit(rng) * from;
    r.d = glm::normalize(Vec3(u(rng), u(rng), u(rng)) - r.o);
  }
  size_t i = 0;
  for (auto _ : state) {
    SurfaceHit hit;
    benchmark::DoNotOptimize(g.intersect(rays[i++ & (kRayCount - 1)], hit));
  }
  state.SetItemsProcessed(state.iterations());
}

void triangleSoupBench(benchmark::State& state, AccelMode mode) {
  SceneGeometry g;
  g.addMesh(triangleSoup(static_cast<int>(state.range(0))), 0);
  g.build(mode);
  intersectBench(state, g);
}
void BM_TrianglesBruteForce(benchmark::State& s) {
  triangleSoupBench(s, AccelMode::BruteForce);
}
void BM_TrianglesEmbree(benchmark::State& s) {
  triangleSoupBench(s, AccelMode::Embree);
}

// A closed mesh: the rock at s = 0 (20 triangles) and s = 1 (80), rays from outside.
void smallRockBench(benchmark::State& state, AccelMode mode) {
  SceneGeometry g;
  g.addMesh(makeRockMesh(static_cast<int>(state.range(0)), 3), 0);
  g.build(mode);
  intersectBench(state, g);
}
void BM_SmallRockBruteForce(benchmark::State& s) {
  smallRockBench(s, AccelMode::BruteForce);
}
void BM_SmallRockEmbree(benchmark::State& s) {
  smallRockBench(s, AccelMode::Embree);
}
BENCHMARK(BM_SmallRockBruteForce)->Arg(0)->Arg(1);
BENCHMARK(BM_SmallRockEmbree)->Arg(0)->Arg(1);
BENCHMARK(BM_TrianglesBruteForce)->Arg(2)->Arg(8)->Arg(16)->Arg(32)->Arg(64)->Arg(128)->Arg(256);
BENCHMARK(BM_TrianglesEmbree)->Arg(2)->Arg(8)->Arg(16)->Arg(32)->Arg(64)->Arg(128)->Arg(256);

// ---- Large rock mesh through Embree ---------------------------------------------------------------
const SceneGeometry& rock(int subdivisions) {
  static std::map<int, std::unique_ptr<SceneGeometry>> cache;
  auto& g = cache[subdivisions];
  if (!g) {
    g = std::make_unique<SceneGeometry>();
    g->addMesh(makeRockMesh(subdivisions, 7), 0);
    g->build();
  }
  return *g;
}

void BM_Rock_OutsideRays(benchmark::State& state) {
  const SceneGeometry& g = rock(static_cast<int>(state.range(0)));
  intersectBench(state, g, 4.f, 5);
  state.counters["triangles"] = static_cast<double>(g.triangleCount());
}
BENCHMARK(BM_Rock_OutsideRays)->Arg(7)->Arg(8);

// AO-style: cosine-ish directions in the hemisphere of surface points, bounded by the scene diagonal.
std::vector<Ray> aoRays(const SceneGeometry& g) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  std::vector<Ray> rays;
  const float tMax = g.bounds().diagonal();
  while (rays.size() < kRayCount) {
    Ray cam{randomUnit(rng) * 4.f, Vec3(0)};
    cam.d = glm::normalize(Vec3(u(rng), u(rng), u(rng)) * 0.5f - cam.o);
    SurfaceHit hit;
    if (!g.intersect(cam, hit)) continue;
    Vec3 w = glm::normalize(hit.ns + randomUnit(rng));
    if (glm::dot(w, hit.ng) <= 0.f) w = -w;
    rays.push_back(Ray{offsetRayOrigin(hit.p, hit.ng, hit.offsetScale, w), w, 0.f, tMax});
  }
  return rays;
}

void BM_Rock_AoOccluded(benchmark::State& state) {
  const SceneGeometry& g = rock(static_cast<int>(state.range(0)));
  std::vector<Ray> rays = aoRays(g);
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(g.occluded(rays[i++ & (kRayCount - 1)]));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Rock_AoOccluded)->Arg(7)->Arg(8);

void BM_Rock_AoIntersect(benchmark::State& state) {
  const SceneGeometry& g = rock(static_cast<int>(state.range(0)));
  std::vector<Ray> rays = aoRays(g);
  size_t i = 0;
  for (auto _ : state) {
    SurfaceHit hit;
    benchmark::DoNotOptimize(g.intersect(rays[i++ & (kRayCount - 1)], hit));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Rock_AoIntersect)->Arg(7)->Arg(8);

void BM_MakeRockMesh(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(makeRockMesh(static_cast<int>(state.range(0)), 7));
}
BENCHMARK(BM_MakeRockMesh)->Arg(7)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace penumbra
