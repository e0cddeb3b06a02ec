// penumbra-mpi: the render subcommand shared by the ranks of an MPI job (app/mpi/distributed_render.h).
// A separate executable, so that `penumbra` never links libmpi or needs mpirun.
#include <cstdio>
#include <exception>

#include "app/mpi/distributed_render.h"
#include "app/mpi/mpi_session.h"
#include "core/math/error.h"

int main(int argc, char** argv) {
  penumbra::mpi::Session session(argc, argv);
  CLI::App app{
      "penumbra-mpi: a Penumbra render split over the ranks of an MPI job (mpirun -np K penumbra-mpi render "
      "...)"};
  app.require_subcommand(1, 1);
  int exitCode = 0;
  penumbra::mpi::addDistributedRenderCommand(app, session, exitCode);
  try {
    app.parse(argc, argv);  // every rank parses the same arguments and fails the same way
  } catch (const CLI::ParseError& e) {
    if (session.rank() == 0) return app.exit(e) == 0 ? 0 : 2;
    return e.get_exit_code() == 0 ? 0 : 2;
  } catch (const std::exception& e) {
    // Failures of a rank after the ranks agreed to render: the job cannot finish its reduction.
    std::fprintf(stderr, "error (rank %d of %d): %s\n", session.rank(), session.size(), e.what());
    session.abort(2);
  }
  return exitCode;
}
