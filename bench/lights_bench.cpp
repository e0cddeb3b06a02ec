// Cost of one sphere-light sample, single thread. items_per_second is samples/s. A projected-solid-
// angle sample includes setting up its cap (ProjectedSphereCap::init), as the integrator does once per
// shading point and light; a solid-angle sample likewise includes its cone.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "core/lights/projected_cap.h"
#include "core/lights/projected_polygon.h"
#include "core/lights/sphere_light.h"
#include "core/lights/spherical_rectangle.h"
#include "core/lights/spherical_triangle.h"

namespace penumbra {
namespace {

constexpr int kCount = 1 << 12;

// Shading points on the plane z = −1 (normal +z) of the hw2 sphere scene's size. Above: the scene's
// light, well above every point's horizon. Straddling: a light whose cap straddles every point's
// horizon, its centre 0.05 above it at distance 3–5 (sin α 0.1–0.17; the cut-disk map). Lens: the
// same light 0.05 below every point's horizon (the lens map). Tiny: the scene's light shrunk to
// sin²α ≈ 1e-6 (0.6e-6–1.4e-6), above the horizon. Grazing: the straddling light with its centre
// 0.007 above every point's horizon (0.08°–0.13°).
enum class Setup { Above, Straddling, Lens, Tiny, Grazing };

struct Fixture {
  SphereLight light{Sphere{Vec3(1, -1.5f, 1.75f), 0.1f}, Color3(300)};
  std::vector<Vec3> points;
  std::vector<Vec2> u;
  explicit Fixture(Setup setup = Setup::Above) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> d(0.f, 0.999f);
    for (int i = 0; i < kCount; ++i) {
      points.push_back(Vec3(2 * d(rng) - 1, 2 * d(rng) - 1, -1.f));
      u.push_back(Vec2(d(rng), d(rng)));
    }
    if (setup == Setup::Straddling || setup == Setup::Lens)
      light.sphere = Sphere{Vec3(4.f, 0.f, -0.95f), 0.5f};
    if (setup == Setup::Lens)
      for (Vec3& p : points) p.z = -0.9f;
    if (setup == Setup::Tiny) light.sphere.radius = 0.0032f;
    if (setup == Setup::Grazing) light.sphere = Sphere{Vec3(4.f, 0.f, -0.993f), 0.5f};
  }
};

template <Setup kSetup>
void BM_SphereLight_SampleSolidAngle(benchmark::State& state) {
  Fixture f(kSetup);
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ & (kCount - 1);
    benchmark::DoNotOptimize(f.light.sampleSolidAngle(f.points[k], f.u[k]));
  }
  state.SetItemsProcessed(state.iterations());
}

template <Setup kSetup>
void BM_SphereLight_SampleProjectedSolidAngle(benchmark::State& state) {
  Fixture f(kSetup);
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ & (kCount - 1);
    ProjectedSphereCap cap;
    cap.init(f.light, f.points[k], Vec3(0, 0, 1));
    benchmark::DoNotOptimize(cap.sample(f.u[k]));
  }
  state.SetItemsProcessed(state.iterations());
}

// Each projected-solid-angle benchmark right after its solid-angle yardstick (same fixture).
BENCHMARK(BM_SphereLight_SampleSolidAngle<Setup::Above>)->Name("BM_SphereLight_SampleSolidAngle");
BENCHMARK(BM_SphereLight_SampleProjectedSolidAngle<Setup::Above>)
    ->Name("BM_SphereLight_SampleProjectedSolidAngle");
BENCHMARK(BM_SphereLight_SampleSolidAngle<Setup::Straddling>)
    ->Name("BM_SphereLight_SampleSolidAngleStraddling");
BENCHMARK(BM_SphereLight_SampleProjectedSolidAngle<Setup::Straddling>)
    ->Name("BM_SphereLight_SampleProjectedSolidAngleStraddling");
BENCHMARK(BM_SphereLight_SampleSolidAngle<Setup::Lens>)->Name("BM_SphereLight_SampleSolidAngleLens");
BENCHMARK(BM_SphereLight_SampleProjectedSolidAngle<Setup::Lens>)
    ->Name("BM_SphereLight_SampleProjectedSolidAngleLens");
BENCHMARK(BM_SphereLight_SampleSolidAngle<Setup::Tiny>)->Name("BM_SphereLight_SampleSolidAngleTiny");
BENCHMARK(BM_SphereLight_SampleProjectedSolidAngle<Setup::Tiny>)
    ->Name("BM_SphereLight_SampleProjectedSolidAngleTiny");
BENCHMARK(BM_SphereLight_SampleSolidAngle<Setup::Grazing>)->Name("BM_SphereLight_SampleSolidAngleGrazing");
BENCHMARK(BM_SphereLight_SampleProjectedSolidAngle<Setup::Grazing>)
    ->Name("BM_SphereLight_SampleProjectedSolidAngleGrazing");

void BM_SphereLight_SampleArea(benchmark::State& state) {
  Fixture f;
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ & (kCount - 1);
    benchmark::DoNotOptimize(f.light.sampleArea(f.points[k], f.u[k]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SphereLight_SampleArea);

// A projected-solid-angle sample of a quad light (ProjectedPolygon: set-up and one sample), from the
// same shading points: above every horizon (the scene light's place, 0.2 across), and a wall quad
// straddling every horizon (x = 4, 1 wide, z from −1.5 to −0.5).
void BM_QuadLight_SampleProjectedSolidAngle(benchmark::State& state) {
  Fixture f;
  const bool straddling = state.range(0) != 0;
  const Vec3 quad[4] = {Vec3(0.9f, -1.6f, 1.75f), Vec3(1.1f, -1.6f, 1.75f), Vec3(1.1f, -1.4f, 1.75f),
                        Vec3(0.9f, -1.4f, 1.75f)};
  const Vec3 wall[4] = {Vec3(4.f, -0.5f, -1.5f), Vec3(4.f, 0.5f, -1.5f), Vec3(4.f, 0.5f, -0.5f),
                        Vec3(4.f, -0.5f, -0.5f)};
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ & (kCount - 1);
    ProjectedPolygon map;
    map.init(straddling ? wall : quad, 4, f.points[k], Vec3(0, 0, 1));
    benchmark::DoNotOptimize(map.sampleDirection(f.u[k]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_QuadLight_SampleProjectedSolidAngle)->Arg(0)->Arg(1);

// A solid-angle sample (Arvo: SphericalTriangle set-up and one sample) of the first half of those quads.
void BM_TriangleLight_SampleSolidAngle(benchmark::State& state) {
  Fixture f;
  const bool straddling = state.range(0) != 0;
  const Vec3 quad[3] = {Vec3(0.9f, -1.6f, 1.75f), Vec3(1.1f, -1.6f, 1.75f), Vec3(1.1f, -1.4f, 1.75f)};
  const Vec3 wall[3] = {Vec3(4.f, -0.5f, -1.5f), Vec3(4.f, 0.5f, -1.5f), Vec3(4.f, 0.5f, -0.5f)};
  const Vec3* t = straddling ? wall : quad;
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ & (kCount - 1);
    SphericalTriangle map;
    map.init(t[0], t[1], t[2], f.points[k]);
    benchmark::DoNotOptimize(map.sampleDirection(f.u[k]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_TriangleLight_SampleSolidAngle)->Arg(0)->Arg(1);

// A solid-angle sample of the whole quads (Ureña et al.: SphericalRectangle set-up and one sample).
void BM_RectangleLight_SampleSolidAngle(benchmark::State& state) {
  Fixture f;
  const bool straddling = state.range(0) != 0;
  const Vec3 corner = straddling ? Vec3(4.f, -0.5f, -1.5f) : Vec3(0.9f, -1.6f, 1.75f);
  const Vec3 edgeU = straddling ? Vec3(0.f, 1.f, 0.f) : Vec3(0.2f, 0.f, 0.f);
  const Vec3 edgeV = straddling ? Vec3(0.f, 0.f, 1.f) : Vec3(0.f, 0.2f, 0.f);
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ & (kCount - 1);
    SphericalRectangle map;
    map.init(corner, edgeU, edgeV, f.points[k]);
    benchmark::DoNotOptimize(map.sampleDirection(f.u[k]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RectangleLight_SampleSolidAngle)->Arg(0)->Arg(1);

// A projected-solid-angle sample (ProjectedPolygon: set-up and one sample) of the same triangles: the
// polygon map's cost against Arvo's for the same shape.
void BM_TriangleLight_SampleProjectedSolidAngle(benchmark::State& state) {
  Fixture f;
  const bool straddling = state.range(0) != 0;
  const Vec3 quad[3] = {Vec3(0.9f, -1.6f, 1.75f), Vec3(1.1f, -1.6f, 1.75f), Vec3(1.1f, -1.4f, 1.75f)};
  const Vec3 wall[3] = {Vec3(4.f, -0.5f, -1.5f), Vec3(4.f, 0.5f, -1.5f), Vec3(4.f, 0.5f, -0.5f)};
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ & (kCount - 1);
    ProjectedPolygon map;
    map.init(straddling ? wall : quad, 3, f.points[k], Vec3(0, 0, 1));
    benchmark::DoNotOptimize(map.sampleDirection(f.u[k]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_TriangleLight_SampleProjectedSolidAngle)->Arg(0)->Arg(1);

}  // namespace
}  // namespace penumbra
