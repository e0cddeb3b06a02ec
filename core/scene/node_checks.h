// Errors about an element of a scene file and the checked property getters every builder uses:
// each error names the file and line of the offending property (or the --set override that gave it).
#pragma once

#include <initializer_list>
#include <span>
#include <string>
#include <string_view>

#include "core/math/vec.h"
#include "core/scene/scene_desc.h"

namespace penumbra {

// An error about a property's value: at the --set override that gave it, else at its line (the
// object's line when the file does not have it).
[[noreturn]] void failProperty(const SceneNode& node, std::span<const std::string_view> names,
                               const std::string& message);
[[noreturn]] void failProperty(const SceneNode& node, std::initializer_list<std::string_view> names,
                               const std::string& message);
// "unknown <tag> type "x" (expected one of: known)" at the element.
[[noreturn]] void unknownType(const SceneNode& node, const char* known);

// A finite float > 0 (>= 0 with allowZero); absent: def.
float getPositiveFloat(const SceneNode& node, std::initializer_list<std::string_view> names, float def,
                       const char* what, bool allowZero = false);
// A finite colour with no negative channel; absent: def.
Color3 getNonNegativeColor(const SceneNode& node, std::initializer_list<std::string_view> names,
                           const Color3& def, const char* what);

}  // namespace penumbra
