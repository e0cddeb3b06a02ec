#include "core/scene/node_checks.h"

#include <cmath>

#include "core/math/error.h"

namespace penumbra {

// An error about a property's value: at the --set override that gave it, else at its line (the
// object's line when the file does not have it).
[[noreturn]] void failProperty(const SceneNode& node, std::span<const std::string_view> names,
                               const std::string& message) {
  if (const Property* p = node.props.find(names); p && !p->setBy.empty())
    throw node.props.errorAt(*p, message);
  int line = node.props.lineOf(names);
  throw Error(node.file, line > 0 ? line : node.line, message);
}

[[noreturn]] void failProperty(const SceneNode& node, std::initializer_list<std::string_view> names,
                               const std::string& message) {
  failProperty(node, std::span<const std::string_view>(names.begin(), names.size()), message);
}

[[noreturn]] void unknownType(const SceneNode& node, const char* known) {
  const std::string message =
      "unknown " + node.tag + " type \"" + node.type + "\" (expected one of: " + known + ")";
  if (!node.typeSetBy.empty()) throw Error(node.typeSetBy + ": " + message);
  throw Error(node.file, node.line, message);
}

float getPositiveFloat(const SceneNode& node, std::initializer_list<std::string_view> names, float def,
                       const char* what, bool allowZero) {
  float v = node.props.getFloat(names, def);
  if (!std::isfinite(v) || v < 0.f || (!allowZero && v == 0.f))
    failProperty(
        node, names,
        std::string(what) + (allowZero ? " must be >= 0" : " must be > 0") + ", got " + std::to_string(v));
  return v;
}

Color3 getNonNegativeColor(const SceneNode& node, std::initializer_list<std::string_view> names,
                           const Color3& def, const char* what) {
  Color3 c = node.props.getColor(names, def);
  if (!(c.x >= 0.f && c.y >= 0.f && c.z >= 0.f) || !std::isfinite(c.x + c.y + c.z))
    failProperty(node, names, std::string(what) + " must be finite and non-negative");
  return c;
}

}  // namespace penumbra
