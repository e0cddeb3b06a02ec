// Ends a rank whose MPI start-up does not complete. Open MPI's MPI_Init waits for every process of
// the job to call it; a process of the job that exits with status 0 without starting MPI (an MPMD
// job's wrong program, a wrapper script that fails quietly) ends no job and would leave every rank
// waiting forever. The watchdog gives the start-up PENUMBRA_MPI_START_TIMEOUT seconds (default
// 120; 0: no limit), then prints why and exits with code 2, which makes mpirun end the job. Rank 0
// reports first; the other ranks wait 5 s longer, as mpirun normally ends them before.
#pragma once

#include <condition_variable>
#include <mutex>
#include <thread>

namespace penumbra::mpi {

inline constexpr double kDefaultStartTimeoutSeconds = 120;

class StartWatchdog {
 public:
  StartWatchdog();   // starts counting
  ~StartWatchdog();  // the start-up completed
  StartWatchdog(const StartWatchdog&) = delete;
  StartWatchdog& operator=(const StartWatchdog&) = delete;

 private:
  std::mutex mutex_;
  std::condition_variable done_;
  bool started_ = false;
  std::thread thread_;
};

}  // namespace penumbra::mpi
