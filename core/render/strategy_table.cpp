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
RayEstimate alongRay(const Scene& scene, const Ray& ray, int samples, int n, uint64_t seed,
                     SamplerKind sampler) {
  return estimateRay(scene, makeIntegrator<Integrator>(samples), ray, n, seed, sampler);
}

// Spellings the assignment's scenes use for each setting.
constexpr Spellings kDirectSamples{{"nSamples", "shadingSamples"}};
constexpr Spellings kAoSamples{{"shadingSamples", "nSamples"}};
constexpr Spellings kMeasure{{"measure"}};
constexpr Spellings kWarp{{"warp-type", "sampling", "sampler", "warp"}};
constexpr Spellings kUniformWarp{{"uniform-hemisphere", "uniform"}};
constexpr Spellings kCosineWarp{{"cosine-hemisphere", "cosine"}};

// A selecting property and the value that picks the row; `orAbsent`: also when the property is left out.
constexpr StrategyProperty when(Spellings name, Spellings value) {
  return {name, value, false};
}
constexpr StrategyProperty whenOrAbsent(Spellings name, Spellings value) {
  return {name, value, true};
}
constexpr StrategyProperty kNone{};

// In enum order (checked below); the order is the one lists and reports show.
constexpr std::array kRows = {
    StrategyRow{
        .strategy = Strategy::DirectUniformHemisphere,
        .label = "direct/uniform-hemisphere",
        .shortName = "uniform-hemisphere",
        .description = "Direct light: directions uniform over the hemisphere (pdf 1/2pi), traced to the "
                       "lights they hit.",
        .xmlType = "direct",
        .samplesProperty = kDirectSamples,
        .select = {{when(kMeasure, {{"hemisphere"}}), when(kWarp, kUniformWarp)}},
        .needs = SceneNeed::Nothing,
        .fallback = Strategy::DirectUniformHemisphere,
        .reference = false,
        .baseline = true,
        .makeRows = rows<DirectIntegrator<Strategy::DirectUniformHemisphere>>,
        .estimateRay = alongRay<DirectIntegrator<Strategy::DirectUniformHemisphere>>,
    },
    StrategyRow{
        .strategy = Strategy::DirectCosineHemisphere,
        .label = "direct/cosine-hemisphere",
        .shortName = "cosine-hemisphere",
        .description =
            "Direct light: cosine-weighted directions (pdf cos/pi), traced to the lights they hit.",
        .xmlType = "direct",
        .samplesProperty = kDirectSamples,
        .select = {{when(kMeasure, {{"hemisphere"}}), whenOrAbsent(kWarp, kCosineWarp)}},
        .needs = SceneNeed::Nothing,
        .fallback = Strategy::DirectCosineHemisphere,
        .reference = false,
        .baseline = false,
        .makeRows = rows<DirectIntegrator<Strategy::DirectCosineHemisphere>>,
        .estimateRay = alongRay<DirectIntegrator<Strategy::DirectCosineHemisphere>>,
    },
    StrategyRow{
        .strategy = Strategy::DirectArea,
        .label = "direct/area",
        .shortName = "area",
        .description =
            "Direct light: uniform points on each light sphere, their pdf converted to solid angle.",
        .xmlType = "direct",
        .samplesProperty = kDirectSamples,
        .select = {{when(kMeasure, {{"area"}}), kNone}},
        .needs = SceneNeed::AreaLights,
        .fallback = Strategy::DirectCosineHemisphere,
        .reference = false,
        .baseline = false,
        .makeRows = rows<DirectIntegrator<Strategy::DirectArea>>,
        .estimateRay = alongRay<DirectIntegrator<Strategy::DirectArea>>,
    },
    StrategyRow{
        .strategy = Strategy::DirectSolidAngle,
        .label = "direct/solid-angle",
        .shortName = "solid-angle",
        .description =
            "Direct light: uniform directions in the cone each light sphere subtends (lowest variance).",
        .xmlType = "direct",
        .samplesProperty = kDirectSamples,
        .select = {{whenOrAbsent(kMeasure, {{"solid-angle", "solidAngle"}}), kNone}},
        .needs = SceneNeed::AreaLights,
        .fallback = Strategy::DirectCosineHemisphere,
        .reference = true,
        .baseline = false,
        .makeRows = rows<DirectIntegrator<Strategy::DirectSolidAngle>>,
        .estimateRay = alongRay<DirectIntegrator<Strategy::DirectSolidAngle>>,
    },
    StrategyRow{
        .strategy = Strategy::AoUniform,
        .label = "ao/uniform",
        .shortName = "ao-uniform",
        .description = "Ambient occlusion: visibility of directions uniform over the hemisphere.",
        .xmlType = "ao",
        .samplesProperty = kAoSamples,
        .select = {{when(kWarp, kUniformWarp), kNone}},
        .needs = SceneNeed::Nothing,
        .fallback = Strategy::AoUniform,
        .reference = false,
        .baseline = true,
        .makeRows = rows<AoIntegrator<Strategy::AoUniform>>,
        .estimateRay = alongRay<AoIntegrator<Strategy::AoUniform>>,
    },
    StrategyRow{
        .strategy = Strategy::AoCosine,
        .label = "ao/cosine",
        .shortName = "ao-cosine",
        .description = "Ambient occlusion: visibility of cosine-weighted directions (lowest variance).",
        .xmlType = "ao",
        .samplesProperty = kAoSamples,
        .select = {{whenOrAbsent(kWarp, kCosineWarp), kNone}},
        .needs = SceneNeed::Nothing,
        .fallback = Strategy::AoCosine,
        .reference = true,
        .baseline = false,
        .makeRows = rows<AoIntegrator<Strategy::AoCosine>>,
        .estimateRay = alongRay<AoIntegrator<Strategy::AoCosine>>,
    },
    StrategyRow{
        .strategy = Strategy::Simple,
        .label = "simple",
        .shortName = "simple",
        .description = "Point and directional lights only, no sampling.",
        .xmlType = "simple",
        .samplesProperty = {},
        .select = {{kNone, kNone}},
        .needs = SceneNeed::Nothing,
        .fallback = Strategy::Simple,
        .reference = false,
        .baseline = false,
        .makeRows = rows<DirectIntegrator<Strategy::Simple>>,
        .estimateRay = alongRay<DirectIntegrator<Strategy::Simple>>,
    },
    StrategyRow{
        .strategy = Strategy::Normals,
        .label = "normals",
        .shortName = "normals",
        .description = "The absolute shading normal as a colour.",
        .xmlType = "normals",
        .samplesProperty = {},
        .select = {{kNone, kNone}},
        .needs = SceneNeed::Nothing,
        .fallback = Strategy::Normals,
        .reference = false,
        .baseline = false,
        .makeRows = rows<NormalsIntegrator>,
        .estimateRay = alongRay<NormalsIntegrator>,
    },
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
