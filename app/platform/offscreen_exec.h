// `penumbra view --offscreen` and `penumbra warp --gui --offscreen` re-run themselves in the sibling
// `penumbra-offscreen` executable (linked with OSMesa instead of libGL), so users type one command.
#pragma once

#include <string>
#include <vector>

namespace penumbra::platform {

// Path of penumbra-offscreen next to the running executable.
std::string offscreenBinary();

// Replaces this process with penumbra-offscreen run with `args` (args[0] excluded: the binary is
// prepended). Returns only by throwing penumbra::Error.
[[noreturn]] void execOffscreen(const std::vector<std::string>& args);

}  // namespace penumbra::platform
