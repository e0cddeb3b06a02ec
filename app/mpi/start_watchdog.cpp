#include "app/mpi/start_watchdog.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace penumbra::mpi {

namespace {

// This process's rank as the launcher gives it (MPI cannot tell before MPI_Init returns); -1 if unknown.
int launcherRank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
    if (const char* value = std::getenv(name)) return std::atoi(value);
  return -1;
}

// PENUMBRA_MPI_START_TIMEOUT in seconds, or the default when unset or not a number >= 0.
double startTimeoutSeconds() {
  const char* text = std::getenv("PENUMBRA_MPI_START_TIMEOUT");
  if (!text || !*text) return kDefaultStartTimeoutSeconds;
  char* end = nullptr;
  const double seconds = std::strtod(text, &end);
  if (*end != '\0' || !(seconds >= 0)) {
    std::fprintf(stderr, "warning: PENUMBRA_MPI_START_TIMEOUT=%s is not a number of seconds; using %g\n",
                 text, kDefaultStartTimeoutSeconds);
    return kDefaultStartTimeoutSeconds;
  }
  return seconds;
}

}  // namespace

StartWatchdog::StartWatchdog() {
  const double timeout = startTimeoutSeconds();
  if (timeout == 0) return;
  const int rank = launcherRank();
  const double wait = timeout + (rank == 0 ? 0.0 : 5.0);
  thread_ = std::thread([this, timeout, wait, rank] {
    std::unique_lock lock(mutex_);
    if (done_.wait_for(lock, std::chrono::duration<double>(wait), [this] { return started_; })) return;
    const std::string who = rank >= 0 ? "rank " + std::to_string(rank) : "a rank";
    std::fprintf(stderr,
                 "error (%s): the MPI job did not start within %g s: some process of the job has not started "
                 "MPI (a program that is not penumbra-mpi, or one that exited?); nothing was rendered or "
                 "written (PENUMBRA_MPI_START_TIMEOUT sets the limit in seconds)\n",
                 who.c_str(), timeout);
    std::fflush(stderr);
    ::_exit(2);  // not exit(): MPI is half started in the main thread
  });
}

StartWatchdog::~StartWatchdog() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard lock(mutex_);
    started_ = true;
  }
  done_.notify_one();
  thread_.join();
}

}  // namespace penumbra::mpi
