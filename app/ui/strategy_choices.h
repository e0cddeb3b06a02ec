// What the viewer offers to render a scene with, from the strategy table: the strategy list (each
// light-sampling measure once), why a strategy cannot light a scene, the light-selection default's
// text, and the strategies compare mode's right side may render.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/integrators/integrator_desc.h"
#include "core/world/scene.h"

namespace penumbra::ui {

// Every row that is its own all-lights row (the rows of one light-sampling measure that differ only
// in lightSelection appear once, as their `all` row), in table order.
std::vector<Strategy> strategyChoices();
// The row `choice` renders with when picked from strategyChoices() while `live` renders: the live
// light selection where both take one, `sceneDefault` where only the choice takes one.
Strategy strategyForChoice(Strategy choice, Strategy live, LightSelection sceneDefault);
// Why `s` cannot light `scene`, for its greyed-out entry in the list ("" when it can): a strategy
// that needs area lights on a scene without them ("needs area lights (renders
// direct/cosine-hemisphere here)"), simple without point or directional lights, the hemisphere
// strategies on a scene without lights.
std::string strategyUnavailableReason(Strategy s, const Scene* scene);
// "default for 64 sphere lights: bvh (all up to 8)".
std::string lightSelectionDefaultText(size_t sphereLights);

// What compare mode's right side may render next to `left`: the strategies of its integrator type
// that have shading samples and apply to the scene, in table order.
std::vector<Strategy> compareChoices(Strategy left, bool sceneHasAreaLights);
// `--compare NAME`: one of compareChoices() by its short name or label, with the left side's shading
// samples; throws penumbra::Error naming the accepted values.
IntegratorDesc parseCompareStrategy(const std::string& name, const IntegratorDesc& left,
                                    bool sceneHasAreaLights);

}  // namespace penumbra::ui
