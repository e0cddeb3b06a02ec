// Light selection as the strategy table expresses it: the rows of one light-sampling measure differ
// only in their lightSelection property (all, uniform, power, bvh). These queries find those rows,
// so the scene builder's default and the viewer's light-selection control switch a row's selection
// without a list of their own.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "core/integrators/integrator_desc.h"
#include "core/math/spellings.h"

namespace penumbra {

// The <integrator> property that chooses the light selection ("lightSelection").
const Spellings& lightSelectionProperty();
// Whether s's row has a lightSelection property (every light-sampling measure of `direct`).
bool takesLightSelection(Strategy s);
// The row of s's integrator type whose selecting properties equal s's except lightSelection, which
// selects `selection`; nullopt when s takes no light selection or the table has no such row.
std::optional<Strategy> withLightSelection(Strategy s, LightSelection selection);
// The row with every light (the base row of s's measure); s itself when s takes no light selection.
Strategy allLightsRow(Strategy s);
// The selections s's measure offers, in table order (empty when s takes none).
std::vector<LightSelection> lightSelectionsOf(Strategy s);
// The canonical lightSelection value that selects `selection` ("all", "bvh", ...), from the table.
std::string_view lightSelectionName(LightSelection selection);

}  // namespace penumbra
