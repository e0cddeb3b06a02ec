// What the viewer offers to render a scene with, from the strategy axes: why a strategy cannot
// light a scene, the light-selection default's text, and what compare mode's right side may render.
#pragma once

#include <cstddef>
#include <string>

#include "core/integrators/integrator_desc.h"
#include "core/world/scene.h"

namespace penumbra::ui {

// Why `s` cannot light `scene`, for its greyed-out entry ("" when it can): a measure that needs area
// lights on a scene without them ("needs area lights (renders direct/cosine-hemisphere here)"),
// simple without point or directional lights, hemisphere directions on a scene without lights.
std::string strategyUnavailableReason(const IntegratorDesc& s, const Scene* scene);
// "default for 64 sphere lights: all (all up to 256)".
std::string lightSelectionDefaultText(size_t areaLights);

// Whether compare mode has something to compare `left` with: its type has sampling axes (direct, ao).
bool offersCompare(const IntegratorDesc& left);
// Whether compare mode's right side may render `right` next to `left`: the same integrator type,
// applicable to the scene.
bool comparable(const IntegratorDesc& right, const IntegratorDesc& left, bool sceneHasAreaLights);
// The right side's strategy when the user chose none: the first of left's type (axis-table order)
// that applies and differs from left; left itself when none does.
IntegratorDesc defaultCompareStrategy(const IntegratorDesc& left, bool sceneHasAreaLights);
// `--compare NAME`: a measure of direct (area, mis, cosine-hemisphere, ...) or a warp of ao, with the
// left side's other axes, or a strategy's short name or label (area-bvh, ao/cosine); it must apply to
// the scene. Throws penumbra::Error naming the accepted values.
IntegratorDesc parseCompareStrategy(const std::string& name, const IntegratorDesc& left,
                                    bool sceneHasAreaLights);

}  // namespace penumbra::ui
