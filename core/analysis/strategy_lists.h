// The strategies `converge` (and Python's converge) compares, from one list per axis, crossed the
// way --samplers crosses: measures (--strategies), and where they apply the light selections, the
// MIS light measures and the heuristics. Old flattened names ("solid-angle-bvh",
// "mis-area-balance") still name their strategy, with a notice that says how to write it now.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/integrators/integrator_desc.h"

namespace penumbra {

// Comma-separated lists; empty takes the scene's value (strategies: every measure).
struct StrategyLists {
  std::string strategies;       // measures of direct, warps of ao, or "all"
  std::string lightSelections;  // crossed with each light measure
  std::string lightMeasures;    // crossed with mis
  std::string heuristics;       // crossed with mis
};

struct ParsedStrategies {
  std::vector<IntegratorDesc> strategies;  // in the order given, each once
  std::vector<std::string> notices;        // one line per old name used
};

// The strategies of base's integrator type (base gives the counts and the axes' defaults). Throws
// Error on an unknown name, naming what each list accepts.
ParsedStrategies parseStrategyLists(const IntegratorDesc& base, const StrategyLists& lists);
// parseStrategyLists with a --strategies list alone, notices dropped.
std::vector<IntegratorDesc> parseStrategies(const IntegratorDesc& base, const std::string& strategies);

// What --strategies offers for `type`: direct's measures, each hemisphere warp on its own
// ("uniform-hemisphere, cosine-hemisphere, area, solid-angle, projected-solid-angle, mis"), ao's
// warps; none for the other types.
std::vector<std::string_view> measureChoices(IntegratorType type);

// "direct: uniform-hemisphere, cosine-hemisphere, area, ...; ao: uniform-hemisphere, cosine-hemisphere":
// what --strategies accepts for each integrator type with strategies to compare.
std::string strategyNamesHelp();

}  // namespace penumbra
