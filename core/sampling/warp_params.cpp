#include "core/sampling/warp_params.h"

#include <cmath>
#include <cstdio>

#include "core/math/error.h"
#include "core/math/float_util.h"

namespace penumbra {

namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// Enough digits to show why a value failed a float check (0.99999999999 is not "1").
std::string preciseNumber(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// Beckmann roughness range in which the float warp and its pdf stay accurate enough for the
// chi-square test at the default resolution (outside it a correct warp is rejected): alpha^2 and
// 1 / (pi alpha^2) lose precision or leave float's range.
constexpr float kBeckmannAlphaMin = 1e-6f, kBeckmannAlphaMax = 1e3f;

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
  // Checked as the float the warp uses: 0.99999999999 passes "< 1" in double but is 1 as a float.
  const float used = toFloatSaturating(value);
  if (type == WarpType::UniformCone && !(used >= -1.f && used < 1.f))
    throw Error("uniform-cone: " + option + " is cos(theta_max) and must be in [-1, 1) as a float " +
                "(at most 0.99999994), got " + preciseNumber(value) +
                (value < 1.0 && used == 1.f ? " (rounds to 1 as a float)" : ""));
  if (type == WarpType::Beckmann && !(used >= kBeckmannAlphaMin && used <= kBeckmannAlphaMax))
    throw Error("beckmann: " + option + " is the roughness alpha and must be in [" +
                number(kBeckmannAlphaMin) + ", " + number(kBeckmannAlphaMax) + "], got " + number(value));
  return used;
}

int checkedLog2Points(int64_t log2Points, const std::string& option) {
  if (log2Points < kMinLog2Points || log2Points > kMaxLog2Points)
    throw Error(option + " " + std::to_string(log2Points) +
                ": expected the number of points as a power of two, " + std::to_string(kMinLog2Points) +
                " to " + std::to_string(kMaxLog2Points) + " (2^" + std::to_string(kMinLog2Points) + " to 2^" +
                std::to_string(kMaxLog2Points) + " points)");
  return int(log2Points);
}

int checkedSamplerRequest(int64_t request, const std::string& option) {
  if (request < 0 || request > kMaxSamplerRequest)
    throw Error(option + " " + std::to_string(request) + ": expected a 2-D request of the sampler, 0 to " +
                std::to_string(kMaxSamplerRequest) + " (0: the pixel filter's)");
  return int(request);
}

IVec2 checkedSamplerPixel(int64_t x, int64_t y, const std::string& option) {
  if (x < 0 || y < 0 || x > kMaxSamplerPixel || y > kMaxSamplerPixel)
    throw Error(option + " " + std::to_string(x) + "," + std::to_string(y) +
                ": expected a pixel X,Y with each coordinate 0 to " + std::to_string(kMaxSamplerPixel));
  return IVec2(int(x), int(y));
}

}  // namespace penumbra
