// The signals that stop a rank's render early, so that rank 0 writes what every rank has rendered:
// SIGINT, SIGTERM, SIGUSR1 (which mpirun forwards to every rank), and a SIGCONT that does not end a
// stop. On Ctrl-C Open MPI 4.1's mpirun sends every rank SIGCONT at once, SIGTERM
// odls_base_sigkill_timeout seconds later (default 1) and SIGKILL as long again after that
// (orte/mca/odls/base/odls_base_default_fns.c, orte_odls_base_default_kill_local_procs): taking the
// SIGCONT as the notice doubles the time left to write. A SIGCONT that resumes a stopped rank (Ctrl-Z,
// then fg) is told apart by a ticker thread's clock readings: a stop leaves a gap of over 1 s.
#pragma once

#include <atomic>
#include <thread>

namespace penumbra::mpi {

class InterruptSignals {
 public:
  // Installs the handlers and starts the ticker; one instance at a time.
  InterruptSignals();
  // Stops the ticker and restores the default actions.
  ~InterruptSignals();
  InterruptSignals(const InterruptSignals&) = delete;
  InterruptSignals& operator=(const InterruptSignals&) = delete;

  bool interrupted() const;
  int signal() const;  // the first interrupting signal; 0: none
  double secondsSinceInterrupt() const;

 private:
  std::atomic<bool> stopTicker_{false};
  std::thread ticker_;
};

}  // namespace penumbra::mpi
