// The axes a rendering strategy is composed of, one small table each: the integrator type, how
// `direct` estimates the area-light integral (its measure), the hemisphere warp, the light measure,
// the light selection and the MIS heuristic. Each row holds a value's spellings (canonical first),
// its help line and what it needs of a scene. The scene builder, the XML and metadata writers, the
// viewer's controls, `converge`, `bench` and the stiff-case catalogue read these tables; none keeps
// its own list, order or spelling. No table lists the combinations: a strategy is an
// IntegratorDesc, and its label, short name and XML properties are composed from its axes.
// Adding a value to an axis: docs/architecture.md, "How to add a light measure" and the recipes
// beside it.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/integrators/integrator_desc.h"
#include "core/math/spellings.h"

namespace penumbra {

// What a scene must have for a strategy to estimate anything beyond delta lights.
enum class SceneNeed : uint8_t { Nothing, AreaLights };
// "needs area lights" (empty for Nothing), for the viewer.
const char* sceneNeedText(SceneNeed need);

struct IntegratorTypeRow {
  IntegratorType type;
  Spellings xmlType;          // <integrator type="...">
  Spellings samplesProperty;  // shading samples per camera sample; empty: the type has none
  std::string_view description;
};

// The values of <integrator type="direct"> `measure`: Hemisphere and Mis have a row each; Light is
// spelled by the light measure itself (measure="area"), from kLightMeasures.
struct EstimatorRow {
  Estimator estimator;
  Spellings measure;  // empty for Light
  SceneNeed needs;
  std::string_view description;
};

struct WarpRow {
  HemisphereWarp warp;
  Spellings spellings;  // warp-type values: "cosine-hemisphere", then "cosine" (the word labels use)
  std::string_view description;
};

struct LightMeasureRow {
  LightMeasure measure;
  Spellings spellings;
  std::string_view description;
};

struct LightSelectionRow {
  LightSelection selection;
  Spellings spellings;
  std::string_view description;
};

struct HeuristicRow {
  MisHeuristic heuristic;
  Spellings spellings;
  std::string_view description;
};

// The <integrator> properties, each spelled once.
inline constexpr Spellings kDirectSamplesProperty{{"nSamples", "shadingSamples"}};
inline constexpr Spellings kAoSamplesProperty{{"shadingSamples", "nSamples"}};
inline constexpr Spellings kMeasureProperty{{"measure"}};
inline constexpr Spellings kWarpProperty{{"warp-type", "sampling", "sampler", "warp"}};
inline constexpr Spellings kLightMeasureProperty{{"lightMeasure"}};
inline constexpr Spellings kLightSelectionProperty{{"lightSelection", "light-selection"}};
inline constexpr Spellings kHeuristicProperty{{"heuristic"}};
inline constexpr Spellings kLightSamplesProperty{{"lightSamples"}};
inline constexpr Spellings kBsdfSamplesProperty{{"bsdfSamples"}};

inline constexpr std::array kIntegratorTypes = {
    IntegratorTypeRow{IntegratorType::Direct,
                      {{"direct"}},
                      kDirectSamplesProperty,
                      "Direct illumination from every emitter."},
    IntegratorTypeRow{IntegratorType::Ao,
                      {{"ao"}},
                      kAoSamplesProperty,
                      "Ambient occlusion: the cosine-weighted visibility of the hemisphere."},
    IntegratorTypeRow{
        IntegratorType::Simple, {{"simple"}}, {}, "Point and directional lights only, no sampling."},
    IntegratorTypeRow{IntegratorType::Normals, {{"normals"}}, {}, "The absolute shading normal as a colour."},
};

// In the order lists, combos and reports show; the first light measure follows Hemisphere.
inline constexpr std::array kEstimators = {
    EstimatorRow{Estimator::Hemisphere,
                 {{"hemisphere"}},
                 SceneNeed::Nothing,
                 "Hemisphere directions traced to the lights they hit."},
    EstimatorRow{
        Estimator::Bsdf,
        {{"bsdf"}},
        SceneNeed::Nothing,
        "The surface's own directions (its BSDF's sampling; cosine on diffuse) traced to the lights."},
    EstimatorRow{
        Estimator::Light, {}, SceneNeed::AreaLights, "Directions towards the lights, by the light measure."},
    EstimatorRow{Estimator::Mis,
                 {{"mis"}},
                 SceneNeed::AreaLights,
                 "Multiple importance sampling of light sampling and BSDF sampling."},
};

inline constexpr std::array kWarps = {
    WarpRow{HemisphereWarp::Uniform,
            {{"uniform-hemisphere", "uniform"}},
            "Directions uniform over the hemisphere (pdf 1/2pi)."},
    WarpRow{HemisphereWarp::Cosine,
            {{"cosine-hemisphere", "cosine"}},
            "Cosine-weighted directions (pdf cos/pi)."},
};

inline constexpr std::array kLightMeasures = {
    LightMeasureRow{LightMeasure::Area,
                    {{"area"}},
                    "Uniform points on each light sphere, their pdf converted to solid angle."},
    LightMeasureRow{LightMeasure::SolidAngle,
                    {{"solid-angle", "solidAngle"}},
                    "Uniform directions in the cone each light sphere subtends (the reference)."},
    LightMeasureRow{LightMeasure::ProjectedSolidAngle,
                    {{"projected-solid-angle", "projectedSolidAngle"}},
                    "Directions in each light's cone with density proportional to cos theta (zero "
                    "variance where the light is unoccluded)."},
};

inline constexpr std::array kLightSelections = {
    LightSelectionRow{LightSelection::All, {{"all"}}, "Every light for every shading sample."},
    LightSelectionRow{LightSelection::Uniform, {{"uniform"}}, "One light per sample, chosen uniformly."},
    LightSelectionRow{
        LightSelection::Power, {{"power"}}, "One light per sample, chosen by emitted power (alias table)."},
    LightSelectionRow{LightSelection::Bvh,
                      {{"bvh"}},
                      "One light per sample, chosen by the light BVH (power, distance and horizon)."},
};

inline constexpr std::array kHeuristics = {
    HeuristicRow{MisHeuristic::Power, {{"power"}}, "Power heuristic (beta = 2)."},
    HeuristicRow{MisHeuristic::Balance, {{"balance"}}, "Balance heuristic."},
};

// The row of a value in its table (every value has one).
const IntegratorTypeRow& rowOf(IntegratorType type);
const EstimatorRow& rowOf(Estimator estimator);
const WarpRow& rowOf(HemisphereWarp warp);
const LightMeasureRow& rowOf(LightMeasure measure);
const LightSelectionRow& rowOf(LightSelection selection);
const HeuristicRow& rowOf(MisHeuristic heuristic);

// The canonical spelling of a value, e.g. "bvh", "solid-angle", "cosine-hemisphere", "direct".
std::string_view nameOf(IntegratorType type);
std::string_view nameOf(HemisphereWarp warp);
std::string_view nameOf(LightMeasure measure);
std::string_view nameOf(LightSelection selection);
std::string_view nameOf(MisHeuristic heuristic);

// The value a spelling names in its table; nullopt for none.
std::optional<IntegratorType> integratorTypeNamed(std::string_view name);
std::optional<HemisphereWarp> warpNamed(std::string_view name);
std::optional<LightMeasure> lightMeasureNamed(std::string_view name);
std::optional<LightSelection> lightSelectionNamed(std::string_view name);
std::optional<MisHeuristic> heuristicNamed(std::string_view name);

// Every spelling a table accepts, "a, b, c", for messages; canonical spellings only without aliases
// (for help texts).
std::string acceptedIntegratorTypes();
std::string acceptedMeasures();
std::string acceptedWarps(bool aliases = true);
std::string acceptedLightMeasures(bool aliases = true);
std::string acceptedLightSelections(bool aliases = true);
std::string acceptedHeuristics(bool aliases = true);

// The value of `measure` a description of `direct` writes: "hemisphere", "mis" or its light measure.
std::string_view measureName(const IntegratorDesc& desc);
// Every value of `measure`, in table order: "hemisphere, area, solid-angle, projected-solid-angle, mis".
std::vector<std::string_view> measureNames();
// What `measure` = name sets (estimator, and the light measure of Light); false for no such value.
bool applyMeasure(std::string_view name, IntegratorDesc& desc);

// The label, e.g. "direct/solid-angle-bvh", "direct/mis/area/power", "ao/cosine".
std::string strategyLabel(const IntegratorDesc& desc);
// A filesystem- and CSV-friendly name, e.g. "solid-angle-bvh", "mis-area-power", "ao-cosine".
std::string strategyShortName(const IntegratorDesc& desc);

// Whether the strategy can render RenderOutput::MisLightShare (MIS).
bool offersLightShare(const IntegratorDesc& desc);
SceneNeed sceneNeed(const IntegratorDesc& desc);
// Whether the strategy estimates what it is meant to in a scene with or without area lights, and
// what renders instead: desc itself, or cosine-hemisphere directions (which see emitters they hit).
bool strategyApplies(const IntegratorDesc& desc, bool sceneHasAreaLights);
IntegratorDesc applicableStrategy(const IntegratorDesc& desc, bool sceneHasAreaLights);
// The lowest-variance strategy of desc's type, which renders references (direct: solid-angle light
// sampling, or MIS of it with BSDF sampling by the power heuristic when some surface is glossy, where
// light sampling alone misses sharp highlights of large lights; ao: cosine), and the naive one
// speed-ups are reported against (uniform hemisphere); desc's counts.
IntegratorDesc referenceStrategy(const IntegratorDesc& desc, bool glossySurfaces = false);
IntegratorDesc baselineStrategy(const IntegratorDesc& desc);
bool isBaseline(const IntegratorDesc& desc);

// Every strategy of desc's type, in table order, with desc's counts: the axes crossed where they
// apply (for `converge --strategies all` with every axis, the image digests and the tests).
std::vector<IntegratorDesc> everyStrategyOfType(const IntegratorDesc& desc);
// everyStrategyOfType of each integrator type in table order, counts 1.
std::vector<IntegratorDesc> everyStrategy();

// The properties that write `desc` back as XML, in canonical spelling: the shading samples (when the
// type has them) and the MIS counts (integers), then each selecting property (strings).
struct CanonicalProperty {
  std::string_view name;
  std::string value;
  bool isInteger;
};
std::vector<CanonicalProperty> canonicalProperties(const IntegratorDesc& desc);
// Whether `property` (any spelling) is one an <integrator> of desc's type can read.
bool integratorReads(const IntegratorDesc& desc, std::string_view property);

}  // namespace penumbra
