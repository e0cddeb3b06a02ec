#include "core/render/strategy_axes.h"

#include <span>

namespace penumbra {

namespace {

template <class Row, size_t N, class Value, class Field>
const Row& find(const std::array<Row, N>& table, Value value, Field field) {
  for (const Row& r : table)
    if (r.*field == value) return r;
  return table.front();  // unreachable for a valid enum value: every value has a row
}

template <class Row, size_t N, class Field>
auto named(const std::array<Row, N>& table, std::string_view name, Spellings Row::*spellings, Field field)
    -> std::optional<std::remove_cvref_t<decltype(table[0].*field)>> {
  for (const Row& r : table)
    if ((r.*spellings).accepts(name)) return r.*field;
  return std::nullopt;
}

template <class Row, size_t N>
std::string accepted(const std::array<Row, N>& table, Spellings Row::*spellings, bool aliases = true) {
  std::string out;
  for (const Row& r : table)
    if (!(r.*spellings).empty())
      (out += out.empty() ? "" : ", ") +=
          aliases ? (r.*spellings).joined() : std::string((r.*spellings).canonical());
  return out;
}

// The warp's short word ("cosine"), its second spelling.
std::string_view warpWord(HemisphereWarp warp) {
  return rowOf(warp).spellings.names[1];
}

}  // namespace

const IntegratorTypeRow& rowOf(IntegratorType type) {
  return find(kIntegratorTypes, type, &IntegratorTypeRow::type);
}
const EstimatorRow& rowOf(Estimator estimator) {
  return find(kEstimators, estimator, &EstimatorRow::estimator);
}
const WarpRow& rowOf(HemisphereWarp warp) {
  return find(kWarps, warp, &WarpRow::warp);
}
const LightMeasureRow& rowOf(LightMeasure measure) {
  return find(kLightMeasures, measure, &LightMeasureRow::measure);
}
const LightSelectionRow& rowOf(LightSelection selection) {
  return find(kLightSelections, selection, &LightSelectionRow::selection);
}
const HeuristicRow& rowOf(MisHeuristic heuristic) {
  return find(kHeuristics, heuristic, &HeuristicRow::heuristic);
}

std::string_view nameOf(IntegratorType type) {
  return rowOf(type).xmlType.canonical();
}
std::string_view nameOf(HemisphereWarp warp) {
  return rowOf(warp).spellings.canonical();
}
std::string_view nameOf(LightMeasure measure) {
  return rowOf(measure).spellings.canonical();
}
std::string_view nameOf(LightSelection selection) {
  return rowOf(selection).spellings.canonical();
}
std::string_view nameOf(MisHeuristic heuristic) {
  return rowOf(heuristic).spellings.canonical();
}

std::optional<IntegratorType> integratorTypeNamed(std::string_view name) {
  return named(kIntegratorTypes, name, &IntegratorTypeRow::xmlType, &IntegratorTypeRow::type);
}
std::optional<HemisphereWarp> warpNamed(std::string_view name) {
  return named(kWarps, name, &WarpRow::spellings, &WarpRow::warp);
}
std::optional<LightMeasure> lightMeasureNamed(std::string_view name) {
  return named(kLightMeasures, name, &LightMeasureRow::spellings, &LightMeasureRow::measure);
}
std::optional<LightSelection> lightSelectionNamed(std::string_view name) {
  return named(kLightSelections, name, &LightSelectionRow::spellings, &LightSelectionRow::selection);
}
std::optional<MisHeuristic> heuristicNamed(std::string_view name) {
  return named(kHeuristics, name, &HeuristicRow::spellings, &HeuristicRow::heuristic);
}

std::string acceptedIntegratorTypes() {
  return accepted(kIntegratorTypes, &IntegratorTypeRow::xmlType);
}
std::string acceptedMeasures() {
  std::string out;
  for (const EstimatorRow& e : kEstimators)
    (out += out.empty() ? "" : ", ") += e.estimator == Estimator::Light
                                            ? accepted(kLightMeasures, &LightMeasureRow::spellings)
                                            : e.measure.joined();
  return out;
}
std::string acceptedWarps(bool aliases) {
  return accepted(kWarps, &WarpRow::spellings, aliases);
}
std::string acceptedLightMeasures(bool aliases) {
  return accepted(kLightMeasures, &LightMeasureRow::spellings, aliases);
}
std::string acceptedLightSelections(bool aliases) {
  return accepted(kLightSelections, &LightSelectionRow::spellings, aliases);
}
std::string acceptedHeuristics(bool aliases) {
  return accepted(kHeuristics, &HeuristicRow::spellings, aliases);
}

const char* sceneNeedText(SceneNeed need) {
  return need == SceneNeed::AreaLights ? "needs area lights" : "";
}

std::string_view measureName(const IntegratorDesc& desc) {
  if (desc.estimator == Estimator::Light) return nameOf(desc.lightMeasure);
  return rowOf(desc.estimator).measure.canonical();
}

std::vector<std::string_view> measureNames() {
  std::vector<std::string_view> out;
  for (const EstimatorRow& e : kEstimators)
    if (e.estimator == Estimator::Light)
      for (const LightMeasureRow& m : kLightMeasures) out.push_back(m.spellings.canonical());
    else
      out.push_back(e.measure.canonical());
  return out;
}

bool applyMeasure(std::string_view name, IntegratorDesc& desc) {
  for (const EstimatorRow& e : kEstimators)
    if (e.measure.accepts(name)) {
      desc.estimator = e.estimator;
      return true;
    }
  if (std::optional<LightMeasure> m = lightMeasureNamed(name)) {
    desc.estimator = Estimator::Light;
    desc.lightMeasure = *m;
    return true;
  }
  return false;
}

std::string strategyLabel(const IntegratorDesc& desc) {
  if (desc.type == IntegratorType::Ao) return "ao/" + std::string(warpWord(desc.warp));
  if (desc.type != IntegratorType::Direct) return std::string(nameOf(desc.type));
  return "direct/" + (desc.estimator == Estimator::Mis ? "mis/" + std::string(nameOf(desc.lightMeasure)) +
                                                             "/" + std::string(nameOf(desc.heuristic))
                                                       : strategyShortName(desc));
}

std::string strategyShortName(const IntegratorDesc& desc) {
  switch (desc.type) {
    case IntegratorType::Ao:
      return "ao-" + std::string(warpWord(desc.warp));
    case IntegratorType::Direct:
      break;
    default:
      return std::string(nameOf(desc.type));
  }
  switch (desc.estimator) {
    case Estimator::Hemisphere:
      return std::string(nameOf(desc.warp));
    case Estimator::Bsdf:
      return std::string(rowOf(desc.estimator).measure.canonical());
    case Estimator::Light:
      return std::string(nameOf(desc.lightMeasure)) + (desc.lightSelection == LightSelection::All
                                                           ? ""
                                                           : "-" + std::string(nameOf(desc.lightSelection)));
    case Estimator::Mis:
      break;
  }
  return "mis-" + std::string(nameOf(desc.lightMeasure)) + "-" + std::string(nameOf(desc.heuristic));
}

bool offersLightShare(const IntegratorDesc& desc) {
  return desc.usesMisAxes();
}

SceneNeed sceneNeed(const IntegratorDesc& desc) {
  return desc.usesEstimator() ? rowOf(desc.estimator).needs : SceneNeed::Nothing;
}

bool strategyApplies(const IntegratorDesc& desc, bool sceneHasAreaLights) {
  return sceneNeed(desc) == SceneNeed::Nothing || sceneHasAreaLights;
}

IntegratorDesc applicableStrategy(const IntegratorDesc& desc, bool sceneHasAreaLights) {
  if (strategyApplies(desc, sceneHasAreaLights)) return desc;
  IntegratorDesc out = desc;
  out.estimator = Estimator::Hemisphere;
  out.warp = HemisphereWarp::Cosine;
  return out;
}

IntegratorDesc referenceStrategy(const IntegratorDesc& desc, bool glossySurfaces) {
  if (desc.type == IntegratorType::Direct && glossySurfaces)
    return withCountsOf(directByMis(LightMeasure::SolidAngle, MisHeuristic::Power), desc);
  if (desc.type == IntegratorType::Direct) return withCountsOf(directByLight(LightMeasure::SolidAngle), desc);
  if (desc.type == IntegratorType::Ao) return withCountsOf(aoBy(HemisphereWarp::Cosine), desc);
  return desc;
}

IntegratorDesc baselineStrategy(const IntegratorDesc& desc) {
  if (desc.type == IntegratorType::Direct)
    return withCountsOf(directByHemisphere(HemisphereWarp::Uniform), desc);
  if (desc.type == IntegratorType::Ao) return withCountsOf(aoBy(HemisphereWarp::Uniform), desc);
  return desc;
}

bool isBaseline(const IntegratorDesc& desc) {
  return desc.usesWarp() && baselineStrategy(desc) == desc;
}

std::vector<IntegratorDesc> everyStrategyOfType(const IntegratorDesc& desc) {
  std::vector<IntegratorDesc> out;
  if (desc.type == IntegratorType::Ao) {
    for (const WarpRow& w : kWarps) out.push_back(withCountsOf(aoBy(w.warp), desc));
    return out;
  }
  if (desc.type != IntegratorType::Direct) return {desc};
  for (const EstimatorRow& e : kEstimators) {
    IntegratorDesc d = desc;
    d.estimator = e.estimator;
    if (e.estimator == Estimator::Hemisphere)
      for (const WarpRow& w : kWarps) d.warp = w.warp, out.push_back(d);
    else if (e.estimator == Estimator::Bsdf)
      out.push_back(d);
    else if (e.estimator == Estimator::Light)
      for (const LightMeasureRow& m : kLightMeasures)
        for (const LightSelectionRow& s : kLightSelections)
          d.lightMeasure = m.measure, d.lightSelection = s.selection, out.push_back(d);
    else
      for (const LightMeasureRow& m : kLightMeasures)
        for (const HeuristicRow& h : kHeuristics)
          d.lightMeasure = m.measure, d.heuristic = h.heuristic, out.push_back(d);
  }
  return out;
}

std::vector<IntegratorDesc> everyStrategy() {
  std::vector<IntegratorDesc> out;
  for (const IntegratorTypeRow& t : kIntegratorTypes)
    for (const IntegratorDesc& d : everyStrategyOfType(integratorOfType(t.type))) out.push_back(d);
  return out;
}

std::vector<CanonicalProperty> canonicalProperties(const IntegratorDesc& desc) {
  std::vector<CanonicalProperty> out;
  const auto integer = [&](const Spellings& name, int value) {
    out.push_back({name.canonical(), std::to_string(value), true});
  };
  const auto string = [&](const Spellings& name, std::string_view value) {
    out.push_back({name.canonical(), std::string(value), false});
  };
  const Spellings& samples = rowOf(desc.type).samplesProperty;
  if (!samples.empty()) integer(samples, desc.samples);
  if (desc.usesMisAxes())
    integer(kLightSamplesProperty, desc.lightSamples), integer(kBsdfSamplesProperty, desc.bsdfSamples);
  if (desc.usesEstimator()) string(kMeasureProperty, measureName(desc));
  if (desc.usesWarp()) string(kWarpProperty, nameOf(desc.warp));
  if (desc.usesLightSelection()) string(kLightSelectionProperty, nameOf(desc.lightSelection));
  if (desc.usesMisAxes())
    string(kLightMeasureProperty, nameOf(desc.lightMeasure)),
        string(kHeuristicProperty, nameOf(desc.heuristic));
  return out;
}

bool integratorReads(const IntegratorDesc& desc, std::string_view property) {
  const auto reads = [&](bool applies, const Spellings& name) { return applies && name.accepts(property); };
  return reads(true, rowOf(desc.type).samplesProperty) || reads(desc.usesEstimator(), kMeasureProperty) ||
         reads(desc.usesWarp(), kWarpProperty) || reads(desc.usesLightSelection(), kLightSelectionProperty) ||
         reads(desc.usesMisAxes(), kLightMeasureProperty) || reads(desc.usesMisAxes(), kHeuristicProperty) ||
         reads(desc.usesMisAxes(), kLightSamplesProperty) || reads(desc.usesMisAxes(), kBsdfSamplesProperty);
}

}  // namespace penumbra
