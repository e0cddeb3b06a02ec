// Cost of one sphere-light sample, single thread. items_per_second is samples/s.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "core/lights/sphere_light.h"

namespace penumbra {
namespace {

constexpr int kCount = 1 << 12;

struct Fixture {
  SphereLight light{Sphere{Vec3(1, -1.5f, 1.75f), 0.1f}, Color3(300)};
  std::vector<Vec3> points;
  std::vector<Vec2> u;
  Fixture() {
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> d(0.f, 0.999f);
    for (int i = 0; i < kCount; ++i) {
      points.push_back(Vec3(2 * d(rng) - 1, 2 * d(rng) - 1, -1.f));
      u.push_back(Vec2(d(rng), d(rng)));
    }
  }
};

void BM_SphereLight_SampleSolidAngle(benchmark::State& state) {
  Fixture f;
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ & (kCount - 1);
    benchmark::DoNotOptimize(f.light.sampleSolidAngle(f.points[k], f.u[k]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SphereLight_SampleSolidAngle);

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

}  // namespace
}  // namespace penumbra
