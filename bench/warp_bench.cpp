// ns per sample of every warp, and of the sampler's per-camera-sample entry points.
#include <benchmark/benchmark.h>

#include "core/sampling/rng.h"
#include "core/sampling/sampler.h"
#include "core/sampling/warp.h"

namespace penumbra {
namespace {

// Pre-generated canonical samples so the timing is the warp alone.
struct Inputs {
  static constexpr int kCount = 4096;
  Vec2 u[kCount];
  Inputs() {
    Rng rng(1, 2);
    for (Vec2& v : u) {
      float a = rng.nextFloat();
      v = Vec2(a, rng.nextFloat());
    }
  }
};
const Inputs& inputs() {
  static const Inputs in;
  return in;
}

void BM_Warp(benchmark::State& state, WarpType type, float param) {
  const Inputs& in = inputs();
  int i = 0;
  for (auto _ : state) {
    Vec3 v = Warp::warp(type, in.u[i], param);
    benchmark::DoNotOptimize(v);
    i = (i + 1) & (Inputs::kCount - 1);
  }
}

void BM_WarpPdf(benchmark::State& state, WarpType type, float param) {
  const Inputs& in = inputs();
  Vec3 v[64];
  for (int k = 0; k < 64; ++k) v[k] = Warp::warp(type, in.u[k], param);
  int i = 0;
  for (auto _ : state) {
    float p = Warp::pdf(type, v[i], param);
    benchmark::DoNotOptimize(p);
    i = (i + 1) & 63;
  }
}

void BM_ConeSin2(benchmark::State& state) {
  const Inputs& in = inputs();
  int i = 0;
  for (auto _ : state) {
    Vec3 v = Warp::squareToUniformConeSin2(in.u[i], 1e-4f);
    benchmark::DoNotOptimize(v);
    i = (i + 1) & (Inputs::kCount - 1);
  }
}

void BM_SamplerStartPixelSample(benchmark::State& state, SamplerKind kind) {
  Sampler s(kind, 16, 7);
  uint32_t i = 0;
  for (auto _ : state) {
    s.startPixelSample(IVec2(static_cast<int>(i & 511), static_cast<int>(i >> 9)), i & 15);
    benchmark::ClobberMemory();
    ++i;
  }
}

void BM_SamplerNext2D(benchmark::State& state, SamplerKind kind) {
  Sampler s(kind, 16, 7);
  uint32_t i = 0;
  s.startPixelSample(IVec2(3, 4), 0);
  for (auto _ : state) {
    Vec2 u = s.next2D();
    benchmark::DoNotOptimize(u);
    if ((++i & 7) == 0) s.startPixelSample(IVec2(3, 4), i >> 3);  // 8 dimensions per pixel sample
  }
}

void BM_SamplerNext1D(benchmark::State& state, SamplerKind kind) {
  Sampler s(kind, 16, 7);
  uint32_t i = 0;
  s.startPixelSample(IVec2(3, 4), 0);
  for (auto _ : state) {
    float u = s.next1D();
    benchmark::DoNotOptimize(u);
    if ((++i & 7) == 0) s.startPixelSample(IVec2(3, 4), i >> 3);
  }
}

BENCHMARK_CAPTURE(BM_Warp, uniform_square, WarpType::UniformSquare, 0.f);
BENCHMARK_CAPTURE(BM_Warp, tent, WarpType::Tent, 0.f);
BENCHMARK_CAPTURE(BM_Warp, uniform_disk, WarpType::UniformDisk, 0.f);
BENCHMARK_CAPTURE(BM_Warp, concentric_disk, WarpType::ConcentricDisk, 0.f);
BENCHMARK_CAPTURE(BM_Warp, uniform_sphere, WarpType::UniformSphere, 0.f);
BENCHMARK_CAPTURE(BM_Warp, uniform_hemisphere, WarpType::UniformHemisphere, 0.f);
BENCHMARK_CAPTURE(BM_Warp, cosine_hemisphere, WarpType::CosineHemisphere, 0.f);
BENCHMARK_CAPTURE(BM_Warp, uniform_cone, WarpType::UniformCone, 0.9f);
BENCHMARK_CAPTURE(BM_Warp, beckmann, WarpType::Beckmann, 0.2f);
BENCHMARK(BM_ConeSin2);
BENCHMARK_CAPTURE(BM_WarpPdf, cosine_hemisphere, WarpType::CosineHemisphere, 0.f);
BENCHMARK_CAPTURE(BM_WarpPdf, uniform_cone, WarpType::UniformCone, 0.9f);
BENCHMARK_CAPTURE(BM_WarpPdf, beckmann, WarpType::Beckmann, 0.2f);
BENCHMARK_CAPTURE(BM_SamplerStartPixelSample, independent, SamplerKind::Independent);
BENCHMARK_CAPTURE(BM_SamplerStartPixelSample, stratified, SamplerKind::Stratified);
BENCHMARK_CAPTURE(BM_SamplerNext2D, independent, SamplerKind::Independent);
BENCHMARK_CAPTURE(BM_SamplerNext2D, stratified, SamplerKind::Stratified);
BENCHMARK_CAPTURE(BM_SamplerNext1D, independent, SamplerKind::Independent);
BENCHMARK_CAPTURE(BM_SamplerNext1D, stratified, SamplerKind::Stratified);

}  // namespace
}  // namespace penumbra
