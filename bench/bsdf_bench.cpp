// Cost of evaluating and of sampling each reflection model, single thread: f(wo, wi) with its density
// (what a light sample's MIS weight needs), and one BSDF sample (direction, f cos θ / pdf and pdf).
// Directions are random over the upper hemisphere; items_per_second is evaluations or samples per s.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "core/materials/bsdf.h"
#include "core/sampling/warp.h"

namespace penumbra {
namespace {

constexpr int kCount = 1 << 12;

enum class Model { Diffuse, Microfacet, Beckmann, Ggx };

Bsdf bsdfOf(Model m) {
  switch (m) {
    case Model::Diffuse:
      return makeDiffuse(Color3(0.5f));
    case Model::Microfacet:
      return makeMicrofacet(Color3(0.3f), 0.1f, 1.5046f, 1.000277f);
    case Model::Beckmann:
      return makeRoughConductor(MicrofacetDistribution::Beckmann, 0.1f, Color3(0.9f));
    case Model::Ggx:
      return makeRoughConductor(MicrofacetDistribution::Ggx, 0.1f, Color3(0.9f));
  }
  return {};
}

struct Directions {
  std::vector<Vec3> wo, wi;
  std::vector<Vec2> u;
  Directions() {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> d(0.f, 0.999f);
    for (int i = 0; i < kCount; ++i) {
      wo.push_back(Warp::squareToCosineHemisphere(Vec2(d(rng), d(rng))));
      wi.push_back(Warp::squareToCosineHemisphere(Vec2(d(rng), d(rng))));
      u.push_back(Vec2(d(rng), d(rng)));
    }
  }
};

template <Model kModel>
void BM_BsdfEvalAndPdf(benchmark::State& state) {
  const Bsdf bsdf = bsdfOf(kModel);
  const Directions dirs;
  int i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(evalBsdf(bsdf, dirs.wo[i], dirs.wi[i]));
    benchmark::DoNotOptimize(pdfBsdf(bsdf, dirs.wo[i], dirs.wi[i]));
    i = (i + 1) & (kCount - 1);
  }
  state.SetItemsProcessed(state.iterations());
}

template <Model kModel>
void BM_BsdfSample(benchmark::State& state) {
  const Bsdf bsdf = bsdfOf(kModel);
  const Directions dirs;
  int i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(sampleBsdf(bsdf, dirs.wo[i], dirs.u[i]));
    i = (i + 1) & (kCount - 1);
  }
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK(BM_BsdfEvalAndPdf<Model::Diffuse>)->Name("BM_BsdfEvalAndPdf/diffuse");
BENCHMARK(BM_BsdfEvalAndPdf<Model::Microfacet>)->Name("BM_BsdfEvalAndPdf/microfacet");
BENCHMARK(BM_BsdfEvalAndPdf<Model::Beckmann>)->Name("BM_BsdfEvalAndPdf/roughconductor_beckmann");
BENCHMARK(BM_BsdfEvalAndPdf<Model::Ggx>)->Name("BM_BsdfEvalAndPdf/roughconductor_ggx");
BENCHMARK(BM_BsdfSample<Model::Diffuse>)->Name("BM_BsdfSample/diffuse");
BENCHMARK(BM_BsdfSample<Model::Microfacet>)->Name("BM_BsdfSample/microfacet");
BENCHMARK(BM_BsdfSample<Model::Beckmann>)->Name("BM_BsdfSample/roughconductor_beckmann");
BENCHMARK(BM_BsdfSample<Model::Ggx>)->Name("BM_BsdfSample/roughconductor_ggx");

}  // namespace
}  // namespace penumbra
