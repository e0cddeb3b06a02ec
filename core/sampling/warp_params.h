// Warp names and parameters as users give them (`penumbra warp`, the Python module): parsing with
// the accepted list in the message, defaults, and range checks that name the offending option.
#pragma once

#include <cstdint>
#include <string>

#include "core/math/vec.h"
#include "core/sampling/warp.h"

namespace penumbra {

// "uniform-square, tent, ...": every warp name, for messages.
std::string warpTypeList();
// Throws Error naming the accepted list when `name` is no warp.
WarpType parseWarpTypeOrThrow(const std::string& name);
// The parameter used when none is given (uniform-cone: cos(theta_max) 0.5; beckmann: alpha 0.2).
float defaultWarpParam(WarpType type);
// Validates the parameter of `type` and returns it as float; throws Error naming `option` when the
// warp takes none but one was given, or when it is out of range.
float checkedWarpParam(WarpType type, bool given, double value, const std::string& option);

// The warp inspector's other inputs (`penumbra warp --gui` and the viewer's inspector window check
// them alike): points as a power of two, the sampler's 2-D request and pixel. Each returns the
// value, or throws Error naming `option` and the accepted range.
inline constexpr int kMinLog2Points = 5, kMaxLog2Points = 20;
inline constexpr int kMaxSamplerRequest = 64;
inline constexpr int kMaxSamplerPixel = 16383;  // the last pixel of the widest image (16384)
int checkedLog2Points(int64_t log2Points, const std::string& option);
int checkedSamplerRequest(int64_t request, const std::string& option);
IVec2 checkedSamplerPixel(int64_t x, int64_t y, const std::string& option);

}  // namespace penumbra
