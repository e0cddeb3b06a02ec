// The strategies: one row each, binding an integrator and its sampling strategy to everything else
// that knows about it (XML spellings, labels, when it applies, how it is instantiated for the row
// loop and for one ray). The scene builder, the XML and metadata writers, the viewer's panels,
// `converge --strategies`, `bench` and the stiff-case catalogue read this table; none keeps its own
// list, order or spelling. Adding a strategy: docs/architecture.md, "How to add a strategy".
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/integrators/integrator_desc.h"
#include "core/math/spellings.h"
#include "core/sampling/sampler.h"

namespace penumbra {

struct Ray;
struct Scene;
struct RenderJob;
struct RowRenderer;

// Mean (of the red channel) +- standard error of an integrator along one ray (core/render/ray_estimator.h).
struct RayEstimate {
  double mean = 0, standardError = 0;
  uint64_t bad = 0;  // NaN / Inf / negative values seen (excluded from the mean)
};

// A string property of <integrator> that selects among the strategies of one integrator type, and
// the value that selects this row.
struct StrategyProperty {
  Spellings name;          // e.g. measure; empty: this level selects nothing
  Spellings value;         // e.g. solid-angle, solidAngle
  bool isDefault = false;  // the value assumed when the property is absent
};

// What a scene must have for the strategy to estimate anything beyond delta lights.
enum class SceneNeed : uint8_t { Nothing, AreaLights };
// "needs area lights" (empty for Nothing), for the viewer.
const char* sceneNeedText(SceneNeed need);

// An integer property of <integrator> beyond the shading samples (the MIS counts), and the field of
// IntegratorDesc it sets; at least 1, default 1 (the field's default).
struct CountProperty {
  Spellings name;  // empty: unused slot
  int IntegratorDesc::*field = nullptr;
};

// Selecting properties per row, read in order, each refining the previous ones.
inline constexpr size_t kMaxSelectors = 3;
inline constexpr size_t kMaxCounts = 2;

struct StrategyRow {
  Strategy strategy;
  std::string_view label;        // "direct/solid-angle": viewer, logs, reports
  std::string_view shortName;    // "solid-angle", "ao-cosine": file names, CSV columns
  std::string_view description;  // one sentence (viewer tooltip)
  std::string_view xmlType;      // <integrator type="...">
  Spellings samplesProperty;     // shading samples per camera sample; empty: the integrator has none
  // Read in order; each refines the ones before (direct: measure, then warp-type for hemisphere,
  // lightSelection for area, solid-angle and projected-solid-angle, or lightMeasure and heuristic
  // for mis).
  std::array<StrategyProperty, kMaxSelectors> select;
  std::array<CountProperty, kMaxCounts> counts =
      {};  // further integer settings (mis: lightSamples, bsdfSamples)
  SceneNeed needs;
  Strategy fallback;  // what renders instead in a scene without what `needs` names
  bool reference;     // the lowest-variance strategy of its integrator type: renders references
  bool baseline;      // the naive strategy of its type that reports measure speed-ups against
  // The row loop and the one-ray estimator with this strategy's integrator: pointers to template
  // instances, so the per-sample code is resolved at compile time.
  RowRenderer (*makeRows)(const RenderJob& job, const IntegratorDesc& desc);
  RayEstimate (*estimateRay)(const Scene& scene, const Ray& ray, int samples, int n, uint64_t seed,
                             SamplerKind sampler);
  // The row loop of the "MIS light share" output (RenderOutput::MisLightShare,
  // core/integrators/mis_light_share.h):
  // the mis rows only; null for every other row, which has no such output.
  RowRenderer (*makeLightShareRows)(const RenderJob& job, const IntegratorDesc& desc) = nullptr;
};

// Every row, in enum order (the order lists, combos and reports show).
std::span<const StrategyRow> strategyTable();
const StrategyRow& strategyRow(Strategy s);
// Whether the strategy can render RenderOutput::MisLightShare (the mis rows).
bool offersLightShare(Strategy s);
// The row's label, e.g. "direct/solid-angle" or "ao/cosine".
std::string strategyLabel(const IntegratorDesc& desc);
// A filesystem- and CSV-friendly name, e.g. "uniform-hemisphere", "solid-angle", "ao-cosine".
std::string strategyShortName(const IntegratorDesc& desc);

// The strategies of one integrator type, in table order (empty for an unknown type).
std::vector<Strategy> strategiesOfType(std::string_view xmlType);
bool sameIntegratorType(Strategy a, Strategy b);
// "direct, ao, simple, normals": the integrator types, for messages.
std::string acceptedIntegratorTypes();

// Whether the strategy estimates what it is meant to in a scene with or without area lights, and
// what to render instead: s itself, or its fallback.
bool strategyApplies(Strategy s, bool sceneHasAreaLights);
Strategy applicableStrategy(Strategy s, bool sceneHasAreaLights);
// The reference (resp. baseline) strategy of s's integrator type; s itself when the type has none.
Strategy referenceStrategy(Strategy s);
Strategy baselineStrategy(Strategy s);

// The properties that write `desc` back as XML, in canonical spelling: the shading samples (when the
// integrator has them, an integer) and each selecting property (strings).
struct CanonicalProperty {
  std::string_view name;
  std::string value;
  bool isInteger;
};
std::vector<CanonicalProperty> canonicalProperties(const IntegratorDesc& desc);

}  // namespace penumbra
