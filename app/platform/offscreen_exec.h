// `penumbra view --offscreen` and `penumbra warp --gui --offscreen` re-run themselves in the sibling
// `penumbra-offscreen` executable (linked with OSMesa instead of libGL), so users type one command.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace penumbra::platform {

// Path of penumbra-offscreen next to the running executable.
std::string offscreenBinary();

// Replaces this process with penumbra-offscreen run with `args` (args[0] excluded: the binary is
// prepended). Returns only by throwing penumbra::Error.
[[noreturn]] void execOffscreen(const std::vector<std::string>& args);

// Where a GUI command runs. In the offscreen build, and in the windowed one when a window can open,
// returns. Otherwise (`offscreen` asked for, or no display, which is said on stderr as
// "COMMAND: why; rendering offscreen instead (OSMesa) and writing OUTPUT") re-runs the command in
// penumbra-offscreen with offscreenArgs() and does not return.
void runOffscreenUnlessWindowed(const char* command, bool offscreen, const std::string& output,
                                const std::function<std::vector<std::string>()>& offscreenArgs);

}  // namespace penumbra::platform
