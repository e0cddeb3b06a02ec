#include "app/mpi/mpi_session.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <thread>

namespace penumbra::mpi {

Session::Session(int& argc, char**& argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
  MPI_Comm_size(node, &localSize_);
  MPI_Comm_free(&node);
}

Session::~Session() {
  MPI_Finalize();
}

namespace {

// Waits for a non-blocking collective, sleeping between tests: a rank that waits for a slower one
// gives its core away instead of spinning in MPI's busy poll (which, on a node shared with the
// rank's own worker threads or other jobs, takes CPU from the work being waited for).
void waitSleeping(MPI_Request& request) {
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

int allreduce(int value, MPI_Op op) {
  int out = value;
  MPI_Request request;
  MPI_Iallreduce(&value, &out, 1, MPI_INT, op, MPI_COMM_WORLD, &request);
  waitSleeping(request);
  return out;
}

constexpr size_t kChunk = size_t(1) << 26;  // elements per MPI_Reduce: far below INT_MAX

void reduceChunks(std::vector<uint64_t>& values, int rank) {
  for (size_t at = 0; at < values.size(); at += kChunk) {
    const int n = int(std::min(kChunk, values.size() - at));
    if (rank == 0)
      MPI_Reduce(MPI_IN_PLACE, values.data() + at, n, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
    else
      MPI_Reduce(values.data() + at, nullptr, n, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
  }
}

}  // namespace

int Session::maxOf(int value) const {
  return allreduce(value, MPI_MAX);
}

int Session::minOf(int value) const {
  return allreduce(value, MPI_MIN);
}

void Session::barrier() const {
  MPI_Request request;
  MPI_Ibarrier(MPI_COMM_WORLD, &request);
  waitSleeping(request);
}

void Session::sumToRoot(const std::vector<double>& values, std::vector<double>& total) const {
  if (rank_ == 0 && total.size() != values.size()) std::abort();  // a caller's bug, not an input error
  for (size_t at = 0; at < values.size(); at += kChunk) {
    const int n = int(std::min(kChunk, values.size() - at));
    MPI_Reduce(values.data() + at, rank_ == 0 ? total.data() + at : nullptr, n, MPI_DOUBLE, MPI_SUM, 0,
               MPI_COMM_WORLD);
  }
}

void Session::sumToRoot(std::vector<uint64_t>& values) const {
  reduceChunks(values, rank_);
}

double Session::wallSeconds() const {
  return MPI_Wtime();
}

void Session::abort(int code) const {
  std::fflush(stdout);
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

}  // namespace penumbra::mpi
