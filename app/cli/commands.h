// Each penumbra subcommand lives in its own file and registers itself on the top-level CLI11 app.
// A command's callback stores its process exit code in `exitCode` (0 ok, 1 check failed, 2 bad input,
// 130 interrupted by Ctrl-C after writing what was complete).
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <string>

#include "core/materials/bsdf_warp.h"
#include "core/sampling/warp.h"

namespace penumbra::cli {

// Process exit codes (docs/commands.md, "Exit codes").
inline constexpr int kExitOk = 0;
inline constexpr int kExitCheckFailed = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitInterrupted = 130;  // 128 + SIGINT, as shells report it

// `penumbra warp --gui` (the warp inspector) needs GL: the executables pass runWarpGui, which lives
// in app/cli/warp_gui_command.cpp with the viewer; without it --gui reports that it is unavailable.
struct WarpGuiArgs {
  WarpType type = WarpType::CosineHemisphere;
  float param = 0.f;
  std::optional<BsdfWarpInputs> bsdf;  // TYPE microfacet | roughconductor (checked)
  int log2Points = 14;
  std::string pointSet = "independent";
  std::string sampler = "sobol";  // --point-set sampler
  int request = 0, pixelX = 0, pixelY = 0;
  bool mismatch = false, gridLines = false;
  uint64_t seed = 1;
  int res = 0;  // 0: automatic
  bool offscreen = false, noWait = false, printLayout = false;
  int frames = -1;
  std::string screenshot, window;
};
using WarpGuiRunner = int (*)(const WarpGuiArgs&);
int runWarpGui(const WarpGuiArgs& args);
void addWarpCommand(CLI::App& app, int& exitCode, WarpGuiRunner gui = nullptr);
void addRenderCommand(CLI::App& app, int& exitCode);
void addBenchCommand(CLI::App& app, int& exitCode);
void addConvergeCommand(CLI::App& app, int& exitCode);
void addCheckCommand(CLI::App& app, int& exitCode);
// Compiled into the penumbra and penumbra-offscreen executables only (it needs GL).
void addViewCommand(CLI::App& app, int& exitCode);

}  // namespace penumbra::cli
