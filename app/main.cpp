// penumbra: one subcommand per file under app/cli/. Built twice: `penumbra` (GLFW window) and
// `penumbra-offscreen` (OSMesa); see app/cli/view_command.cpp.
#include <cstdio>
#include <exception>
#include <new>

#include "app/cli/commands.h"
#include "core/math/error.h"

int main(int argc, char** argv) {
  CLI::App app{"Penumbra: an interactive, progressive Monte Carlo renderer for studying light sampling"};
  app.require_subcommand(0, 1);
  int exitCode = 0;
  penumbra::cli::addWarpCommand(app, exitCode, penumbra::cli::runWarpGui);
  penumbra::cli::addRenderCommand(app, exitCode);
  penumbra::cli::addBenchCommand(app, exitCode);
  penumbra::cli::addConvergeCommand(app, exitCode);
  penumbra::cli::addCheckCommand(app, exitCode);
  penumbra::cli::addViewCommand(app, exitCode);

  // `penumbra` with no arguments opens the viewer on the built-in scene.
  char viewArg[] = "view";
  char* viewArgv[] = {argv[0], viewArg, nullptr};
  if (argc == 1) {
    argc = 2;
    argv = viewArgv;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int rc = app.exit(e);
    return rc == 0 ? 0 : 2;  // bad arguments are exit code 2, like bad input files
  } catch (const penumbra::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr,
                 "error: out of memory (a render's size is checked first; this was something else)\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  if (app.get_subcommands().empty()) {
    std::printf("%s", app.help().c_str());
    return 0;
  }
  return exitCode;
}
