#include "core/render/strategy_table.h"

#include "core/render/light_selection_rows.h"

#include "core/integrators/ao_integrator.h"
#include "core/integrators/direct_integrator.h"
#include "core/integrators/mis_integrator.h"
#include "core/integrators/mis_light_share.h"
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

// The MIS integrators take both counts from the description; the one-ray estimator's `samples` sets
// both (tests and the stiff catalogue run one of each).
template <LightMeasure kMeasure, MisHeuristic kHeuristic>
RowRenderer misRows(const RenderJob& job, const IntegratorDesc& desc) {
  return rowsFor(job, MisIntegrator<kMeasure, kHeuristic>{desc.lightSamples, desc.bsdfSamples});
}

template <LightMeasure kMeasure, MisHeuristic kHeuristic>
RowRenderer misLightShareRows(const RenderJob& job, const IntegratorDesc& desc) {
  return rowsFor(job, MisLightShareIntegrator<kMeasure, kHeuristic>{{desc.lightSamples, desc.bsdfSamples}});
}

template <LightMeasure kMeasure, MisHeuristic kHeuristic>
RayEstimate misAlongRay(const Scene& scene, const Ray& ray, int samples, int n, uint64_t seed,
                        SamplerKind sampler) {
  return estimateRay(scene, MisIntegrator<kMeasure, kHeuristic>{samples, samples}, ray, n, seed, sampler);
}

// Spellings the assignment's scenes use for each setting.
constexpr Spellings kDirectSamples{{"nSamples", "shadingSamples"}};
constexpr Spellings kAoSamples{{"shadingSamples", "nSamples"}};
constexpr Spellings kMeasure{{"measure"}};
constexpr Spellings kWarp{{"warp-type", "sampling", "sampler", "warp"}};
constexpr Spellings kUniformWarp{{"uniform-hemisphere", "uniform"}};
constexpr Spellings kCosineWarp{{"cosine-hemisphere", "cosine"}};
constexpr Spellings kLightSelection{{"lightSelection", "light-selection"}};
constexpr Spellings kAllLights{{"all"}};

// A selecting property and the value that picks the row; `orAbsent`: also when the property is left out.
constexpr StrategyProperty when(Spellings name, Spellings value) {
  return {name, value, false};
}
constexpr StrategyProperty whenOrAbsent(Spellings name, Spellings value) {
  return {name, value, true};
}
constexpr StrategyProperty kNone{};

constexpr Spellings kLightMeasure{{"lightMeasure"}};
constexpr Spellings kHeuristic{{"heuristic"}};
constexpr Spellings kSolidAngleValue{{"solid-angle", "solidAngle"}};
constexpr Spellings kAreaValue{{"area"}};
constexpr Spellings kProjectedValue{{"projected-solid-angle", "projectedSolidAngle"}};
constexpr std::array<CountProperty, kMaxCounts> kMisCounts = {{
    {{{"lightSamples"}}, &IntegratorDesc::lightSamples},
    {{{"bsdfSamples"}}, &IntegratorDesc::bsdfSamples},
}};

// measure = mis, lightMeasure (solid-angle when absent), heuristic (power when absent). No
// lightSelection: MIS samples every light (core/integrators/mis_integrator.h says why).
constexpr std::array<StrategyProperty, kMaxSelectors> misSelect(Spellings light, bool lightDefault,
                                                                bool power) {
  return {{when(kMeasure, {{"mis"}}),
           {kLightMeasure, light, lightDefault},
           {kHeuristic, power ? Spellings{{"power"}} : Spellings{{"balance"}}, power}}};
}

template <LightMeasure kMeasure, MisHeuristic kH>
constexpr StrategyRow misRow(Strategy strategy, std::string_view label, std::string_view shortName,
                             std::string_view description, Spellings light, bool lightDefault) {
  return StrategyRow{
      .strategy = strategy,
      .label = label,
      .shortName = shortName,
      .description = description,
      .xmlType = "direct",
      .samplesProperty = kDirectSamples,
      .select = misSelect(light, lightDefault, kH == MisHeuristic::Power),
      .counts = kMisCounts,
      .needs = SceneNeed::AreaLights,
      .fallback = Strategy::DirectCosineHemisphere,
      .reference = false,
      .baseline = false,
      .makeRows = misRows<kMeasure, kH>,
      .estimateRay = misAlongRay<kMeasure, kH>,
      .makeLightShareRows = misLightShareRows<kMeasure, kH>,
  };
}

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
        .select = {{when(kMeasure, {{"area"}}), whenOrAbsent(kLightSelection, kAllLights)}},
        .needs = SceneNeed::AreaLights,
        .fallback = Strategy::DirectCosineHemisphere,
        .reference = false,
        .baseline = false,
        .makeRows = rows<DirectIntegrator<Strategy::DirectArea>>,
        .estimateRay = alongRay<DirectIntegrator<Strategy::DirectArea>>,
    },
    StrategyRow{
        .strategy = Strategy::DirectAreaUniform,
        .label = "direct/area-uniform",
        .shortName = "area-uniform",
        .description = "Direct light: a uniform point on one light sphere per sample, chosen uniformly.",
        .xmlType = "direct",
        .samplesProperty = kDirectSamples,
        .select = {{when(kMeasure, {{"area"}}), when(kLightSelection, {{"uniform"}})}},
        .needs = SceneNeed::AreaLights,
        .fallback = Strategy::DirectCosineHemisphere,
        .reference = false,
        .baseline = false,
        .makeRows = rows<DirectIntegrator<Strategy::DirectAreaUniform>>,
        .estimateRay = alongRay<DirectIntegrator<Strategy::DirectAreaUniform>>,
    },
    StrategyRow{
        .strategy = Strategy::DirectAreaPower,
        .label = "direct/area-power",
        .shortName = "area-power",
        .description = "Direct light: a uniform point on one light sphere per sample, chosen by emitted "
                       "power (alias table).",
        .xmlType = "direct",
        .samplesProperty = kDirectSamples,
        .select = {{when(kMeasure, {{"area"}}), when(kLightSelection, {{"power"}})}},
        .needs = SceneNeed::AreaLights,
        .fallback = Strategy::DirectCosineHemisphere,
        .reference = false,
        .baseline = false,
        .makeRows = rows<DirectIntegrator<Strategy::DirectAreaPower>>,
        .estimateRay = alongRay<DirectIntegrator<Strategy::DirectAreaPower>>,
    },
    StrategyRow{
        .strategy = Strategy::DirectAreaBvh,
        .label = "direct/area-bvh",
        .shortName = "area-bvh",
        .description = "Direct light: a uniform point on one light sphere per sample, chosen by the light "
                       "BVH (power, distance and horizon).",
        .xmlType = "direct",
        .samplesProperty = kDirectSamples,
        .select = {{when(kMeasure, {{"area"}}), when(kLightSelection, {{"bvh"}})}},
        .needs = SceneNeed::AreaLights,
        .fallback = Strategy::DirectCosineHemisphere,
        .reference = false,
        .baseline = false,
        .makeRows = rows<DirectIntegrator<Strategy::DirectAreaBvh>>,
        .estimateRay = alongRay<DirectIntegrator<Strategy::DirectAreaBvh>>,
    },
    StrategyRow{
        .strategy = Strategy::DirectSolidAngle,
        .label = "direct/solid-angle",
        .shortName = "solid-angle",
        .description = "Direct light: uniform directions in the cone each light sphere subtends (the "
                       "reference strategy).",
        .xmlType = "direct",
        .samplesProperty = kDirectSamples,
        .select = {{whenOrAbsent(kMeasure, {{"solid-angle", "solidAngle"}}),
                    whenOrAbsent(kLightSelection, kAllLights)}},
        .needs = SceneNeed::AreaLights,
        .fallback = Strategy::DirectCosineHemisphere,
        .reference = true,
        .baseline = false,
        .makeRows = rows<DirectIntegrator<Strategy::DirectSolidAngle>>,
        .estimateRay = alongRay<DirectIntegrator<Strategy::DirectSolidAngle>>,
    },
    StrategyRow{
        .strategy = Strategy::DirectSolidAngleUniform,
        .label = "direct/solid-angle-uniform",
        .shortName = "solid-angle-uniform",
        .description =
            "Direct light: a uniform direction in the cone of one light per sample, chosen uniformly.",
        .xmlType = "direct",
        .samplesProperty = kDirectSamples,
        .select = {{when(kMeasure, {{"solid-angle", "solidAngle"}}), when(kLightSelection, {{"uniform"}})}},
        .needs = SceneNeed::AreaLights,
        .fallback = Strategy::DirectCosineHemisphere,
        .reference = false,
        .baseline = false,
        .makeRows = rows<DirectIntegrator<Strategy::DirectSolidAngleUniform>>,
        .estimateRay = alongRay<DirectIntegrator<Strategy::DirectSolidAngleUniform>>,
    },
    StrategyRow{
        .strategy = Strategy::DirectSolidAnglePower,
        .label = "direct/solid-angle-power",
        .shortName = "solid-angle-power",
        .description = "Direct light: a uniform direction in the cone of one light per sample, chosen by "
                       "emitted power (alias table).",
        .xmlType = "direct",
        .samplesProperty = kDirectSamples,
        .select = {{when(kMeasure, {{"solid-angle", "solidAngle"}}), when(kLightSelection, {{"power"}})}},
        .needs = SceneNeed::AreaLights,
        .fallback = Strategy::DirectCosineHemisphere,
        .reference = false,
        .baseline = false,
        .makeRows = rows<DirectIntegrator<Strategy::DirectSolidAnglePower>>,
        .estimateRay = alongRay<DirectIntegrator<Strategy::DirectSolidAnglePower>>,
    },
    StrategyRow{
        .strategy = Strategy::DirectSolidAngleBvh,
        .label = "direct/solid-angle-bvh",
        .shortName = "solid-angle-bvh",
        .description = "Direct light: a uniform direction in the cone of one light per sample, chosen by the "
                       "light BVH (power, distance and horizon).",
        .xmlType = "direct",
        .samplesProperty = kDirectSamples,
        .select = {{when(kMeasure, {{"solid-angle", "solidAngle"}}), when(kLightSelection, {{"bvh"}})}},
        .needs = SceneNeed::AreaLights,
        .fallback = Strategy::DirectCosineHemisphere,
        .reference = false,
        .baseline = false,
        .makeRows = rows<DirectIntegrator<Strategy::DirectSolidAngleBvh>>,
        .estimateRay = alongRay<DirectIntegrator<Strategy::DirectSolidAngleBvh>>,
    },
    StrategyRow{
        .strategy = Strategy::DirectProjectedSolidAngle,
        .label = "direct/projected-solid-angle",
        .shortName = "projected-solid-angle",
        .description = "Direct light: directions in each light's cone with density proportional to cos theta "
                       "(zero variance where the light is unoccluded).",
        .xmlType = "direct",
        .samplesProperty = kDirectSamples,
        .select = {{when(kMeasure, kProjectedValue), whenOrAbsent(kLightSelection, kAllLights)}},
        .needs = SceneNeed::AreaLights,
        .fallback = Strategy::DirectCosineHemisphere,
        .reference = false,
        .baseline = false,
        .makeRows = rows<DirectIntegrator<Strategy::DirectProjectedSolidAngle>>,
        .estimateRay = alongRay<DirectIntegrator<Strategy::DirectProjectedSolidAngle>>,
    },
    StrategyRow{
        .strategy = Strategy::DirectProjectedSolidAngleUniform,
        .label = "direct/projected-solid-angle-uniform",
        .shortName = "projected-solid-angle-uniform",
        .description =
            "Direct light: a direction in the cone of one light per sample with density proportional to "
            "cos theta, the light chosen uniformly.",
        .xmlType = "direct",
        .samplesProperty = kDirectSamples,
        .select = {{when(kMeasure, kProjectedValue), when(kLightSelection, {{"uniform"}})}},
        .needs = SceneNeed::AreaLights,
        .fallback = Strategy::DirectCosineHemisphere,
        .reference = false,
        .baseline = false,
        .makeRows = rows<DirectIntegrator<Strategy::DirectProjectedSolidAngleUniform>>,
        .estimateRay = alongRay<DirectIntegrator<Strategy::DirectProjectedSolidAngleUniform>>,
    },
    StrategyRow{
        .strategy = Strategy::DirectProjectedSolidAnglePower,
        .label = "direct/projected-solid-angle-power",
        .shortName = "projected-solid-angle-power",
        .description =
            "Direct light: a direction in the cone of one light per sample with density proportional to "
            "cos theta, the light chosen by emitted power (alias table).",
        .xmlType = "direct",
        .samplesProperty = kDirectSamples,
        .select = {{when(kMeasure, kProjectedValue), when(kLightSelection, {{"power"}})}},
        .needs = SceneNeed::AreaLights,
        .fallback = Strategy::DirectCosineHemisphere,
        .reference = false,
        .baseline = false,
        .makeRows = rows<DirectIntegrator<Strategy::DirectProjectedSolidAnglePower>>,
        .estimateRay = alongRay<DirectIntegrator<Strategy::DirectProjectedSolidAnglePower>>,
    },
    StrategyRow{
        .strategy = Strategy::DirectProjectedSolidAngleBvh,
        .label = "direct/projected-solid-angle-bvh",
        .shortName = "projected-solid-angle-bvh",
        .description =
            "Direct light: a direction in the cone of one light per sample with density proportional to "
            "cos theta, the light chosen by the light BVH (power, distance and horizon).",
        .xmlType = "direct",
        .samplesProperty = kDirectSamples,
        .select = {{when(kMeasure, kProjectedValue), when(kLightSelection, {{"bvh"}})}},
        .needs = SceneNeed::AreaLights,
        .fallback = Strategy::DirectCosineHemisphere,
        .reference = false,
        .baseline = false,
        .makeRows = rows<DirectIntegrator<Strategy::DirectProjectedSolidAngleBvh>>,
        .estimateRay = alongRay<DirectIntegrator<Strategy::DirectProjectedSolidAngleBvh>>,
    },
    misRow<LightMeasure::SolidAngle, MisHeuristic::Power>(
        Strategy::DirectMisSolidAnglePower, "direct/mis/solid-angle/power", "mis-solid-angle-power",
        "Direct light: MIS of solid-angle light sampling and cosine directions, power heuristic.",
        kSolidAngleValue, true),
    misRow<LightMeasure::SolidAngle, MisHeuristic::Balance>(
        Strategy::DirectMisSolidAngleBalance, "direct/mis/solid-angle/balance", "mis-solid-angle-balance",
        "Direct light: MIS of solid-angle light sampling and cosine directions, balance heuristic.",
        kSolidAngleValue, true),
    misRow<LightMeasure::Area, MisHeuristic::Power>(
        Strategy::DirectMisAreaPower, "direct/mis/area/power", "mis-area-power",
        "Direct light: MIS of area light sampling and cosine directions, power heuristic.", kAreaValue,
        false),
    misRow<LightMeasure::Area, MisHeuristic::Balance>(
        Strategy::DirectMisAreaBalance, "direct/mis/area/balance", "mis-area-balance",
        "Direct light: MIS of area light sampling and cosine directions, balance heuristic.", kAreaValue,
        false),
    misRow<LightMeasure::ProjectedSolidAngle, MisHeuristic::Power>(
        Strategy::DirectMisProjectedPower, "direct/mis/projected-solid-angle/power",
        "mis-projected-solid-angle-power",
        "Direct light: MIS of projected-solid-angle light sampling and cosine directions, power heuristic.",
        kProjectedValue, false),
    misRow<LightMeasure::ProjectedSolidAngle, MisHeuristic::Balance>(
        Strategy::DirectMisProjectedBalance, "direct/mis/projected-solid-angle/balance",
        "mis-projected-solid-angle-balance",
        "Direct light: MIS of projected-solid-angle light sampling and cosine directions, balance heuristic.",
        kProjectedValue, false),
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

bool offersLightShare(Strategy s) {
  return strategyRow(s).makeLightShareRows != nullptr;
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
  for (const CountProperty& c : r.counts)
    if (!c.name.empty()) out.push_back({c.name.canonical(), std::to_string(desc.*c.field), true});
  for (const StrategyProperty& p : r.select)
    if (!p.name.empty()) out.push_back({p.name.canonical(), std::string(p.value.canonical()), false});
  return out;
}

const Spellings& lightSelectionProperty() {
  return kLightSelection;
}

}  // namespace penumbra
