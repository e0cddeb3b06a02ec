#include "core/sampling/warp_params.h"

#include <cmath>
#include <cstdio>

#include "core/math/error.h"

namespace penumbra {

namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

std::string warpTypeList() {
  std::string s;
  for (int i = 0; i < kWarpTypeCount; ++i) {
    if (i) s += ", ";
    s += warpTypeName(static_cast<WarpType>(i));
  }
  return s;
}

WarpType parseWarpTypeOrThrow(const std::string& name) {
  WarpType t;
  if (!parseWarpType(name, t))
    throw Error("unknown warp type '" + name + "' (expected one of: " + warpTypeList() + ")");
  return t;
}

float defaultWarpParam(WarpType type) {
  return type == WarpType::Beckmann ? 0.2f : 0.5f;
}

float checkedWarpParam(WarpType type, bool given, double value, const std::string& option) {
  if (!warpHasParameter(type)) {
    if (given)
      throw Error(std::string("warp '") + warpTypeName(type) + "' takes no parameter (" + option + ")");
    return 0.f;
  }
  if (!given) return defaultWarpParam(type);
  if (type == WarpType::UniformCone && !(value >= -1.0 && value < 1.0))
    throw Error("uniform-cone: " + option + " is cos(theta_max) and must be in [-1, 1), got " +
                number(value));
  if (type == WarpType::Beckmann && !(value > 0.0 && std::isfinite(value)))
    throw Error("beckmann: " + option + " is the roughness alpha and must be > 0, got " + number(value));
  return static_cast<float>(value);
}

}  // namespace penumbra
