// Each penumbra subcommand lives in its own file and registers itself on the top-level CLI11 app.
// A command's callback stores its process exit code in `exitCode` (0 ok, 1 check failed, 2 bad input).
#pragma once

#include <CLI/CLI.hpp>

namespace penumbra::cli {

void addWarpCommand(CLI::App& app, int& exitCode);
void addRenderCommand(CLI::App& app, int& exitCode);
void addBenchCommand(CLI::App& app, int& exitCode);
void addConvergeCommand(CLI::App& app, int& exitCode);
void addCheckCommand(CLI::App& app, int& exitCode);
// Compiled into the penumbra and penumbra-offscreen executables only (it needs GL).
void addViewCommand(CLI::App& app, int& exitCode);

}  // namespace penumbra::cli
