#include "core/render/strategy_table.h"

#include "core/integrators/ao_integrator.h"
#include "core/integrators/direct_integrator.h"
#include "core/integrators/normals_integrator.h"
#include "core/render/ray_estimator.h"
#include "core/render/row_loop.h"

namespace penumbra {

namespace {

template <class Integrator>
Integrator makeIntegrator(int samples) {
  if constexpr (requires { Integrator{samples}; })
    return Integrator{samples};
  else
    return Integrator{};
}

template <class Integrator>
RowRenderer rows(const RenderJob& job, const IntegratorDesc& desc) {
  return rowsFor(job, makeIntegrator<Integrator>(desc.samples));
}

template <class Integrator>
RayEstimate alongRay(const Scene& scene, const Ray& ray, int samples, int n, uint64_t seed) {
  return estimateRay(scene, makeIntegrator<Integrator>(samples), ray, n, seed);
}

// Spellings the assignment's scenes use for each setting.
constexpr Spellings kDirectSamples{{"nSamples", "shadingSamples"}};
constexpr Spellings kAoSamples{{"shadingSamples", "nSamples"}};
constexpr Spellings kMeasure{{"measure"}};
constexpr Spellings kWarp{{"warp-type", "sampling", "sampler", "warp"}};
constexpr Spellings kUniformWarp{{"uniform-hemisphere", "uniform"}};
constexpr Spellings kCosineWarp{{"cosine-hemisphere", "cosine"}};

constexpr StrategyProperty kNone{};

// In enum order (checked below); the order is the one lists and reports show.
constexpr std::array kRows = {
    StrategyRow{Strategy::DirectUniformHemisphere,
                "direct/uniform-hemisphere",
                "uniform-hemisphere",
                "Direct light: directions uniform over the hemisphere (pdf 1/2pi), traced to the lights they "
                "hit.",
                "direct",
                kDirectSamples,
                {{{kMeasure, {{"hemisphere"}}, false}, {kWarp, kUniformWarp, false}}},
                SceneNeed::Nothing,
                Strategy::DirectUniformHemisphere,
                false,
                true,
                rows<DirectIntegrator<Strategy::DirectUniformHemisphere>>,
                alongRay<DirectIntegrator<Strategy::DirectUniformHemisphere>>},
    StrategyRow{Strategy::DirectCosineHemisphere,
                "direct/cosine-hemisphere",
                "cosine-hemisphere",
                "Direct light: cosine-weighted directions (pdf cos/pi), traced to the lights they hit.",
                "direct",
                kDirectSamples,
                {{{kMeasure, {{"hemisphere"}}, false}, {kWarp, kCosineWarp, true}}},
                SceneNeed::Nothing,
                Strategy::DirectCosineHemisphere,
                false,
                false,
                rows<DirectIntegrator<Strategy::DirectCosineHemisphere>>,
                alongRay<DirectIntegrator<Strategy::DirectCosineHemisphere>>},
    StrategyRow{Strategy::DirectArea,
                "direct/area",
                "area",
                "Direct light: uniform points on each light sphere, their pdf converted to solid angle.",
                "direct",
                kDirectSamples,
                {{{kMeasure, {{"area"}}, false}, kNone}},
                SceneNeed::AreaLights,
                Strategy::DirectCosineHemisphere,
                false,
                false,
                rows<DirectIntegrator<Strategy::DirectArea>>,
                alongRay<DirectIntegrator<Strategy::DirectArea>>},
    StrategyRow{Strategy::DirectSolidAngle,
                "direct/solid-angle",
                "solid-angle",
                "Direct light: uniform directions in the cone each light sphere subtends (lowest variance).",
                "direct",
                kDirectSamples,
                {{{kMeasure, {{"solid-angle", "solidAngle"}}, true}, kNone}},
                SceneNeed::AreaLights,
                Strategy::DirectCosineHemisphere,
                true,
                false,
                rows<DirectIntegrator<Strategy::DirectSolidAngle>>,
                alongRay<DirectIntegrator<Strategy::DirectSolidAngle>>},
    StrategyRow{Strategy::AoUniform,
                "ao/uniform",
                "ao-uniform",
                "Ambient occlusion: visibility of directions uniform over the hemisphere.",
                "ao",
                kAoSamples,
                {{{kWarp, kUniformWarp, false}, kNone}},
                SceneNeed::Nothing,
                Strategy::AoUniform,
                false,
                true,
                rows<AoIntegrator<Strategy::AoUniform>>,
                alongRay<AoIntegrator<Strategy::AoUniform>>},
    StrategyRow{Strategy::AoCosine,
                "ao/cosine",
                "ao-cosine",
                "Ambient occlusion: visibility of cosine-weighted directions (lowest variance).",
                "ao",
                kAoSamples,
                {{{kWarp, kCosineWarp, true}, kNone}},
                SceneNeed::Nothing,
                Strategy::AoCosine,
                true,
                false,
                rows<AoIntegrator<Strategy::AoCosine>>,
                alongRay<AoIntegrator<Strategy::AoCosine>>},
    StrategyRow{Strategy::Simple,
                "simple",
                "simple",
                "Point and directional lights only, no sampling.",
                "simple",
                {},
                {{kNone, kNone}},
                SceneNeed::Nothing,
                Strategy::Simple,
                false,
                false,
                rows<DirectIntegrator<Strategy::Simple>>,
                alongRay<DirectIntegrator<Strategy::Simple>>},
    StrategyRow{Strategy::Normals,
                "normals",
                "normals",
                "The absolute shading normal as a colour.",
                "normals",
                {},
                {{kNone, kNone}},
                SceneNeed::Nothing,
                Strategy::Normals,
                false,
                false,
                rows<NormalsIntegrator>,
                alongRay<NormalsIntegrator>},
};
static_assert(kRows.size() == size_t(kStrategyCount));
static_assert([] {
  for (size_t i = 0; i < kRows.size(); ++i)
    if (size_t(kRows[i].strategy) != i) return false;
  return true;
}());

}  // namespace

std::span<const StrategyRow> strategyTable() {
  return kRows;
}

const StrategyRow& strategyRow(Strategy s) {
  return kRows[size_t(s)];
}

std::string strategyLabel(const IntegratorDesc& desc) {
  return std::string(strategyRow(desc.strategy).label);
}

std::string strategyShortName(const IntegratorDesc& desc) {
  return std::string(strategyRow(desc.strategy).shortName);
}

std::vector<Strategy> strategiesOfType(std::string_view xmlType) {
  std::vector<Strategy> out;
  for (const StrategyRow& r : kRows)
    if (r.xmlType == xmlType) out.push_back(r.strategy);
  return out;
}

bool sameIntegratorType(Strategy a, Strategy b) {
  return strategyRow(a).xmlType == strategyRow(b).xmlType;
}

std::string acceptedIntegratorTypes() {
  std::string out;
  for (size_t i = 0; i < kRows.size(); ++i) {
    bool seen = false;
    for (size_t j = 0; j < i; ++j) seen = seen || kRows[j].xmlType == kRows[i].xmlType;
    if (!seen) (out += out.empty() ? "" : ", ") += kRows[i].xmlType;
  }
  return out;
}

const char* sceneNeedText(SceneNeed need) {
  return need == SceneNeed::AreaLights ? "needs area lights" : "";
}

bool strategyApplies(Strategy s, bool sceneHasAreaLights) {
  return strategyRow(s).needs == SceneNeed::Nothing || sceneHasAreaLights;
}

Strategy applicableStrategy(Strategy s, bool sceneHasAreaLights) {
  return strategyApplies(s, sceneHasAreaLights) ? s : strategyRow(s).fallback;
}

Strategy referenceStrategy(Strategy s) {
  for (const StrategyRow& r : kRows)
    if (r.reference && sameIntegratorType(r.strategy, s)) return r.strategy;
  return s;
}

Strategy baselineStrategy(Strategy s) {
  for (const StrategyRow& r : kRows)
    if (r.baseline && sameIntegratorType(r.strategy, s)) return r.strategy;
  return s;
}

std::vector<CanonicalProperty> canonicalProperties(const IntegratorDesc& desc) {
  const StrategyRow& r = strategyRow(desc.strategy);
  std::vector<CanonicalProperty> out;
  if (!r.samplesProperty.empty())
    out.push_back({r.samplesProperty.canonical(), std::to_string(desc.samples), true});
  for (const StrategyProperty& p : r.select)
    if (!p.name.empty()) out.push_back({p.name.canonical(), std::string(p.value.canonical()), false});
  return out;
}

}  // namespace penumbra
