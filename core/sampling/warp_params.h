// Warp names and parameters as users give them (`penumbra warp`, the Python module): parsing with
// the accepted list in the message, defaults, and range checks that name the offending option.
#pragma once

#include <string>

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

}  // namespace penumbra
