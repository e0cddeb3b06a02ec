// penumbra-mpi: the render subcommand shared by the ranks of an MPI job (app/mpi/distributed_render.h).
// A separate executable, so that `penumbra` never links libmpi or needs mpirun.
#include <cstdio>
#include <exception>
#include <sstream>

#include "app/mpi/distributed_render.h"
#include "app/mpi/mpi_session.h"
#include "app/mpi/rank_agreement.h"

namespace {

// What parsing the arguments on this rank gave: the help text (--help) or the error message.
struct ParseOutcome {
  std::string help, failure;
};

ParseOutcome parseArguments(CLI::App& app, int argc, char** argv) {
  ParseOutcome outcome;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    std::ostringstream out, err;
    if (app.exit(e, out, err) == 0)
      outcome.help = out.str();
    else
      outcome.failure = err.str().empty() ? out.str() : err.str();
  }
  return outcome;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace penumbra::mpi;
  Session session(argc, argv);
  CLI::App app{
      "penumbra-mpi: a Penumbra render split over the ranks of an MPI job (mpirun -np K penumbra-mpi render "
      "...)"};
  app.require_subcommand(1, 1);
  DistributedRenderOptions options;
  addDistributedRenderCommand(app, options);
  // Each rank parses its own arguments (an MPMD job gives ranks different ones), then every rank
  // takes part in the agreement whatever its parse gave: a rank that leaves on a bad argument would
  // leave the others waiting for it in their first collective.
  const ParseOutcome parsed = parseArguments(app, argc, argv);
  if (!everyRankSucceeded(session, parsed.failure)) return kExitBadInput;
  const int helpRanks = session.sumOf(parsed.help.empty() ? 0 : 1);
  if (helpRanks == session.size()) {
    if (session.rank() == 0) std::printf("%s", parsed.help.c_str());
    return 0;
  }
  if (helpRanks > 0 &&
      !everyRankSucceeded(session, parsed.help.empty() ? "" : "--help given, but not to every rank"))
    return kExitBadInput;
  try {
    return runDistributedRender(options, session);
  } catch (const std::exception& e) {
    // Failures of a rank after the ranks agreed to render: the job cannot finish its reduction.
    std::fprintf(stderr, "error (rank %d of %d): %s\n", session.rank(), session.size(), e.what());
    session.abort(kExitBadInput);
  }
}
