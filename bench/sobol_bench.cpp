// The sampler work of camera samples with independent, stratified, sobol and zsobol streams, in the
// same run: next2D streams (8 requests per pixel sample) and a camera sample's draws (restart, the
// filter's pair, one light pair), with the pixel moving along a row as in the renderer.
#include <benchmark/benchmark.h>

#include "core/sampling/sampler.h"
#include "core/sampling/sobol_sampler.h"

namespace penumbra {
namespace {

template <class S>
S makeSampler();
template <>
Sampler makeSampler<Sampler>() {
  return Sampler(SamplerKind::Independent, 16, 7);
}
struct StratifiedSampler : Sampler {
  StratifiedSampler() : Sampler(SamplerKind::Stratified, 16, 7) {}
};
template <>
StratifiedSampler makeSampler<StratifiedSampler>() {
  return StratifiedSampler();
}
template <>
SobolSampler makeSampler<SobolSampler>() {
  return SobolSampler(7);
}
template <>
ZSobolSampler makeSampler<ZSobolSampler>() {
  return ZSobolSampler(16, 7);
}

template <class S>
void BM_Next2DStream(benchmark::State& state) {
  S s = makeSampler<S>();
  uint32_t i = 0;
  s.startPixelSample(IVec2(3, 4), 0);
  for (auto _ : state) {
    Vec2 u = s.next2D();
    benchmark::DoNotOptimize(u);
    if ((++i & 7) == 0) s.startPixelSample(IVec2(static_cast<int>((i >> 3) & 511), 4), i >> 12);
  }
  state.SetItemsProcessed(state.iterations());
}

template <class S>
void BM_CameraSampleDraws(benchmark::State& state) {
  S s = makeSampler<S>();
  uint32_t i = 0;
  for (auto _ : state) {
    s.startPixelSample(IVec2(static_cast<int>(i & 511), 4), i >> 9);
    Vec2 filter = s.next2D();
    Vec2 light = s.next2D();
    benchmark::DoNotOptimize(filter);
    benchmark::DoNotOptimize(light);
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK_TEMPLATE(BM_Next2DStream, Sampler)->Name("Next2DStream/independent");
BENCHMARK_TEMPLATE(BM_Next2DStream, StratifiedSampler)->Name("Next2DStream/stratified");
BENCHMARK_TEMPLATE(BM_Next2DStream, SobolSampler)->Name("Next2DStream/sobol");
BENCHMARK_TEMPLATE(BM_Next2DStream, ZSobolSampler)->Name("Next2DStream/zsobol");
BENCHMARK_TEMPLATE(BM_CameraSampleDraws, Sampler)->Name("CameraSampleDraws/independent");
BENCHMARK_TEMPLATE(BM_CameraSampleDraws, StratifiedSampler)->Name("CameraSampleDraws/stratified");
BENCHMARK_TEMPLATE(BM_CameraSampleDraws, SobolSampler)->Name("CameraSampleDraws/sobol");
BENCHMARK_TEMPLATE(BM_CameraSampleDraws, ZSobolSampler)->Name("CameraSampleDraws/zsobol");

}  // namespace
}  // namespace penumbra
