#include "core/render/light_selection_rows.h"

#include "core/render/strategy_table.h"

namespace penumbra {

namespace {

bool isLightSelection(const StrategyProperty& p) {
  return !p.name.empty() && p.name.names == lightSelectionProperty().names;
}

// Whether rows a and b select alike on every property but lightSelection (spellings, not defaults:
// the base row's measure may be the one assumed when absent).
bool sameButLightSelection(const StrategyRow& a, const StrategyRow& b) {
  if (a.xmlType != b.xmlType || a.select.size() != b.select.size()) return false;
  for (size_t i = 0; i < a.select.size(); ++i) {
    const StrategyProperty &p = a.select[i], &q = b.select[i];
    if (p.name.names != q.name.names) return false;
    if (!isLightSelection(p) && p.value.names != q.value.names) return false;
  }
  return true;
}

}  // namespace

bool takesLightSelection(Strategy s) {
  for (const StrategyProperty& p : strategyRow(s).select)
    if (isLightSelection(p)) return true;
  return false;
}

std::optional<Strategy> withLightSelection(Strategy s, LightSelection selection) {
  if (!takesLightSelection(s)) return std::nullopt;
  const StrategyRow& from = strategyRow(s);
  for (const StrategyRow& r : strategyTable())
    if (lightSelectionOf(r.strategy) == selection && sameButLightSelection(from, r)) return r.strategy;
  return std::nullopt;
}

Strategy allLightsRow(Strategy s) {
  return withLightSelection(s, LightSelection::All).value_or(s);
}

std::vector<LightSelection> lightSelectionsOf(Strategy s) {
  std::vector<LightSelection> out;
  if (!takesLightSelection(s)) return out;
  for (const StrategyRow& r : strategyTable())
    if (sameButLightSelection(strategyRow(s), r)) out.push_back(lightSelectionOf(r.strategy));
  return out;
}

std::string_view lightSelectionName(LightSelection selection) {
  for (const StrategyRow& r : strategyTable())
    if (lightSelectionOf(r.strategy) == selection)
      for (const StrategyProperty& p : r.select)
        if (isLightSelection(p)) return p.value.canonical();
  return {};
}

}  // namespace penumbra
