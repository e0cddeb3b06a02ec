// penumbra: one executable, one subcommand per file under app/cli/.
#include <cstdio>
#include <exception>

#include "app/cli/commands.h"
#include "core/math/error.h"

int main(int argc, char** argv) {
  CLI::App app{"Penumbra: an interactive, progressive Monte Carlo renderer for studying light sampling"};
  app.require_subcommand(0, 1);
  int exitCode = 0;
  penumbra::cli::addWarpCommand(app, exitCode);
  penumbra::cli::addRenderCommand(app, exitCode);
  penumbra::cli::addBenchCommand(app, exitCode);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int rc = app.exit(e);
    return rc == 0 ? 0 : 2;  // bad arguments are exit code 2, like bad input files
  } catch (const penumbra::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
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
