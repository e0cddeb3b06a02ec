#include "core/analysis/strategy_lists.h"

#include <algorithm>
#include <optional>
#include <sstream>

#include "core/math/error.h"
#include "core/render/strategy_axes.h"

namespace penumbra {

namespace {

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream ss(list);
  for (std::string name; std::getline(ss, name, ',');)
    if (!name.empty()) out.push_back(name);
  return out;
}

std::string joined(const std::vector<std::string_view>& names) {
  std::string out;
  for (std::string_view n : names) (out += out.empty() ? "" : ", ") += n;
  return out;
}

// The measures --strategies offers for direct: each warp of the hemisphere, then the others.
std::vector<std::string_view> directMeasures() {
  std::vector<std::string_view> out;
  for (std::string_view m : measureNames())
    if (m == rowOf(Estimator::Hemisphere).measure.canonical())
      for (const WarpRow& w : kWarps) out.push_back(w.spellings.canonical());
    else
      out.push_back(m);
  return out;
}

std::vector<std::string_view> warpNames() {
  std::vector<std::string_view> out;
  for (const WarpRow& w : kWarps) out.push_back(w.spellings.canonical());
  return out;
}

// One axis's list: each name's value, or the default when the list is empty.
template <class Value>
std::vector<Value> axisList(const std::string& list, Value def,
                            std::optional<Value> (*lookup)(std::string_view), const char* axis,
                            const std::string& accepted) {
  if (list.empty()) return {def};
  std::vector<Value> out;
  for (const std::string& name : split(list)) {
    std::optional<Value> v = lookup(name);
    if (!v)
      throw Error(std::string("unknown ") + axis + " \"" + name + "\" (expected some of: " + accepted + ")");
    if (std::find(out.begin(), out.end(), *v) == out.end()) out.push_back(*v);
  }
  if (out.empty()) throw Error(std::string("the ") + axis + " list names nothing");
  return out;
}

// The descriptions a --strategies name stands for before crossing (one, or both hemisphere warps),
// false when it is no axis value.
bool measureStrategies(const IntegratorDesc& base, const std::string& name,
                       std::vector<IntegratorDesc>& out) {
  IntegratorDesc d = base;
  // ao's warps may carry its short name's prefix ("ao-cosine"); direct takes a warp for the
  // hemisphere measure with that warp.
  const bool ao = base.type == IntegratorType::Ao;
  const std::string_view word = ao && name.rfind("ao-", 0) == 0 ? std::string_view(name).substr(3) : name;
  if (std::optional<HemisphereWarp> w = warpNamed(word)) {
    if (!ao) d.estimator = Estimator::Hemisphere;
    d.warp = *w;
    out.push_back(d);
    return true;
  }
  if (ao) return false;
  if (!applyMeasure(name, d)) return false;
  if (d.estimator == Estimator::Hemisphere)
    for (const WarpRow& w : kWarps) d.warp = w.warp, out.push_back(d);
  else
    out.push_back(d);
  return true;
}

// How an old flattened name is written with the axes, e.g. "--strategies area --light-selection bvh".
std::string axesSpelling(const IntegratorDesc& d) {
  if (d.type == IntegratorType::Ao) return "--strategies " + std::string(nameOf(d.warp));
  if (d.estimator == Estimator::Hemisphere) return "--strategies " + std::string(nameOf(d.warp));
  std::string out = "--strategies " + std::string(measureName(d));
  if (d.estimator == Estimator::Bsdf) return out;
  if (d.estimator == Estimator::Light)
    return out + " --light-selection " + std::string(nameOf(d.lightSelection));
  return out + " --light-measure " + std::string(nameOf(d.lightMeasure)) + " --heuristic " +
         std::string(nameOf(d.heuristic));
}

// The strategy an old flattened name (a label with or without its type, or a short name) names.
std::optional<IntegratorDesc> oldName(const IntegratorDesc& base, const std::string& name) {
  for (const IntegratorDesc& d : everyStrategyOfType(base)) {
    const std::string label = strategyLabel(d);
    if (name == label || name == strategyShortName(d) || name == label.substr(label.find('/') + 1)) return d;
  }
  return std::nullopt;
}

void addOnce(std::vector<IntegratorDesc>& out, const IntegratorDesc& d) {
  if (std::find(out.begin(), out.end(), d) == out.end()) out.push_back(d);
}

}  // namespace

ParsedStrategies parseStrategyLists(const IntegratorDesc& base, const StrategyLists& lists) {
  if (everyStrategyOfType(base).size() < 2)
    throw Error("converge: the " + std::string(nameOf(base.type)) +
                " integrator has no sampling strategies to compare (use direct or ao)");
  const IntegratorDesc defaults;
  const std::vector<LightSelection> selections =
      axisList(lists.lightSelections, base.lightSelection, lightSelectionNamed, "light selection",
               acceptedLightSelections());
  const std::vector<LightMeasure> misMeasures =
      axisList(lists.lightMeasures, base.usesMisAxes() ? base.lightMeasure : defaults.lightMeasure,
               lightMeasureNamed, "light measure", acceptedLightMeasures());
  const std::vector<MisHeuristic> heuristics =
      axisList(lists.heuristics, base.heuristic, heuristicNamed, "heuristic", acceptedHeuristics());

  std::vector<std::string> names = split(lists.strategies);
  if (names.empty() || (names.size() == 1 && names[0] == "all")) {
    names.clear();
    for (std::string_view n : measureChoices(base.type)) names.emplace_back(n);
  }
  ParsedStrategies out;
  for (const std::string& name : names) {
    std::vector<IntegratorDesc> measures;
    if (measureStrategies(base, name, measures)) {
      for (IntegratorDesc d : measures) {
        if (d.usesLightSelection())
          for (LightSelection s : selections) d.lightSelection = s, addOnce(out.strategies, d);
        else if (d.usesMisAxes())
          for (LightMeasure m : misMeasures)
            for (MisHeuristic h : heuristics) d.lightMeasure = m, d.heuristic = h, addOnce(out.strategies, d);
        else
          addOnce(out.strategies, d);
      }
    } else if (std::optional<IntegratorDesc> d = oldName(base, name)) {
      addOnce(out.strategies, *d);
      out.notices.push_back("converge: \"" + name + "\" is an old name; write " + axesSpelling(*d));
    } else {
      throw Error("unknown strategy \"" + name + "\" (expected all, or a comma-separated list of: " +
                  joined(measureChoices(base.type)) + ")");
    }
  }
  return out;
}

std::vector<IntegratorDesc> parseStrategies(const IntegratorDesc& base, const std::string& strategies) {
  return parseStrategyLists(base, {strategies, "", "", ""}).strategies;
}

std::vector<std::string_view> measureChoices(IntegratorType type) {
  if (type == IntegratorType::Direct) return directMeasures();
  if (type == IntegratorType::Ao) return warpNames();
  return {};
}

std::string strategyNamesHelp() {
  return std::string(nameOf(IntegratorType::Direct)) + ": " + joined(measureChoices(IntegratorType::Direct)) +
         "; " + std::string(nameOf(IntegratorType::Ao)) + ": " + joined(measureChoices(IntegratorType::Ao));
}

}  // namespace penumbra
