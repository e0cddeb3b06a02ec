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
#include "core/scene/scaling_scene.h"

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

// ---- Brute force vs Embree on small triangle and parallelogram soups (kBruteForceMaxPrimitives) --
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
// n random parallelograms, each two triangles sharing a diagonal (the flat loop tests each pair once).
TriangleMesh parallelogramSoup(int n) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  TriangleMesh m;
  for (int i = 0; i < n; ++i) {
    const Vec3 c(u(rng), u(rng), u(rng)), e0 = 0.3f * Vec3(u(rng), u(rng), u(rng)),
                                          e1 = 0.3f * Vec3(u(rng), u(rng), u(rng));
    for (const Vec3& p : {c, c + e0, c + e0 + e1, c + e1}) m.positions.push_back(p);
    const unsigned b = 4 * i;
    m.triangles.push_back({b, b + 1, b + 2});
    m.triangles.push_back({b, b + 2, b + 3});
  }
  return m;
}
void parallelogramSoupBench(benchmark::State& state, AccelMode mode) {
  SceneGeometry g;
  g.addMesh(parallelogramSoup(static_cast<int>(state.range(0))), 0);
  g.build(mode);
  if (mode == AccelMode::BruteForce && g.parallelogramCount() != size_t(state.range(0)))
    state.SkipWithError("the soup's triangles did not pair");
  intersectBench(state, g);
}
void BM_ParallelogramsBruteForce(benchmark::State& s) {
  parallelogramSoupBench(s, AccelMode::BruteForce);
}
void BM_ParallelogramsEmbree(benchmark::State& s) {
  parallelogramSoupBench(s, AccelMode::Embree);
}
BENCHMARK(BM_ParallelogramsBruteForce)->Arg(2)->Arg(4)->Arg(8)->Arg(16)->Arg(32);
BENCHMARK(BM_ParallelogramsEmbree)->Arg(2)->Arg(4)->Arg(8)->Arg(16)->Arg(32);

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

// ---- Brute force vs BVH for spheres (justifies kBruteForceMaxSpheres) ------------------------------
// The scaling scene's geometry (range(0) lights plus as many blockers over a two-triangle floor):
// camera rays onto the floor, and shadow rays from floor points to points on the lights (skipping
// the light itself, as the integrator does).
struct SphereScene {
  SceneGeometry geometry;
  std::vector<Ray> cameraRays, shadowRays;
  std::vector<int32_t> shadowSkip;
};

SphereScene sphereScene(int lights, AccelMode sphereMode) {
  SphereScene s;
  std::vector<ScalingSphere> spheres = scalingSceneSpheres(lights, 1);
  for (size_t i = 0; i < spheres.size(); ++i) s.geometry.addSphere(spheres[i].sphere, uint32_t(i));
  s.geometry.addMesh(makeGridPlane(Vec3(-10, 0, 10), Vec3(20, 0, 0), Vec3(0, 0, -20), 1, 1), 1u << 30);
  s.geometry.build(AccelMode::Auto, sphereMode);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  const Vec3 eye(0, 16, 17);
  while (s.cameraRays.size() < kRayCount) {
    const Ray cam{eye, glm::normalize(Vec3(10 * u(rng), 0, 10 * u(rng)) - eye)};
    s.cameraRays.push_back(cam);
    SurfaceHit hit;
    if (!s.geometry.intersect(cam, hit)) continue;
    const int light = 2 * int(std::uniform_int_distribution<int>(0, lights - 1)(rng));
    const Sphere& ls = spheres[size_t(light)].sphere;
    const Vec3 target = ls.center + ls.radius * randomUnit(rng);
    const Vec3 o = offsetRayOrigin(hit.p, hit.ng, hit.offsetScale, target - hit.p);
    const float len = glm::length(target - o);
    s.shadowRays.push_back(Ray{o, (target - o) / len, 0.f, len * (1.f - 1e-4f)});
    s.shadowSkip.push_back(light);
  }
  return s;
}

void sphereIntersectBench(benchmark::State& state, AccelMode sphereMode) {
  const SphereScene s = sphereScene(static_cast<int>(state.range(0)), sphereMode);
  size_t i = 0;
  for (auto _ : state) {
    SurfaceHit hit;
    benchmark::DoNotOptimize(s.geometry.intersect(s.cameraRays[i++ & (kRayCount - 1)], hit));
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["spheres"] = static_cast<double>(s.geometry.sphereCount());
}
void sphereOccludedBench(benchmark::State& state, AccelMode sphereMode) {
  const SphereScene s = sphereScene(static_cast<int>(state.range(0)), sphereMode);
  const size_t n = s.shadowRays.size();
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.geometry.occluded(s.shadowRays[i], s.shadowSkip[i]));
    if (++i == n) i = 0;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["spheres"] = static_cast<double>(s.geometry.sphereCount());
}
void BM_SpheresBruteForce_Intersect(benchmark::State& s) {
  sphereIntersectBench(s, AccelMode::BruteForce);
}
void BM_SpheresBvh_Intersect(benchmark::State& s) {
  sphereIntersectBench(s, AccelMode::Embree);
}
void BM_SpheresBruteForce_Occluded(benchmark::State& s) {
  sphereOccludedBench(s, AccelMode::BruteForce);
}
void BM_SpheresBvh_Occluded(benchmark::State& s) {
  sphereOccludedBench(s, AccelMode::Embree);
}
// Arg: lights (spheres = 2 × lights).
#define PENUMBRA_SPHERE_COUNTS \
  ->Arg(1)->Arg(2)->Arg(3)->Arg(4)->Arg(6)->Arg(8)->Arg(12)->Arg(16)->Arg(64)->Arg(500)->Arg(5000)
BENCHMARK(BM_SpheresBruteForce_Intersect) PENUMBRA_SPHERE_COUNTS;
BENCHMARK(BM_SpheresBvh_Intersect) PENUMBRA_SPHERE_COUNTS;
BENCHMARK(BM_SpheresBruteForce_Occluded) PENUMBRA_SPHERE_COUNTS;
BENCHMARK(BM_SpheresBvh_Occluded) PENUMBRA_SPHERE_COUNTS;
#undef PENUMBRA_SPHERE_COUNTS

void BM_MakeRockMesh(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(makeRockMesh(static_cast<int>(state.range(0)), 7));
}
BENCHMARK(BM_MakeRockMesh)->Arg(7)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace penumbra
