#include "app/mpi/mpi_session.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "app/mpi/start_watchdog.h"

namespace penumbra::mpi {

Session::Session(int& argc, char**& argv) {
  const StartWatchdog watchdog;  // MPI_Init and the split below wait for every process of the job
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

int Session::sumOf(int value) const {
  return allreduce(value, MPI_SUM);
}

std::vector<uint64_t> Session::allGather(uint64_t value) const {
  std::vector<uint64_t> all(size_t(size_), 0);
  MPI_Request request;
  MPI_Iallgather(&value, 1, MPI_UINT64_T, all.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD, &request);
  waitSleeping(request);
  return all;
}

std::string Session::broadcastFromRoot(const std::string& text) const {
  uint64_t length = rank_ == 0 ? text.size() : 0;
  MPI_Request request;
  MPI_Ibcast(&length, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD, &request);
  waitSleeping(request);
  if (length > uint64_t(INT_MAX)) abort(2);  // a run description of over 2 GB: not a real scene
  std::string out = rank_ == 0 ? text : std::string(length, '\0');
  MPI_Ibcast(out.data(), int(length), MPI_CHAR, 0, MPI_COMM_WORLD, &request);
  waitSleeping(request);
  return out;
}

std::vector<std::string> Session::gatherToRoot(const std::string& text) const {
  const int length = int(std::min<size_t>(text.size(), INT_MAX / size_t(size_)));
  std::vector<int> lengths(rank_ == 0 ? size_t(size_) : 0), offsets(lengths.size());
  MPI_Request request;
  MPI_Igather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
  waitSleeping(request);
  std::string all;
  if (rank_ == 0) {
    for (size_t r = 1; r < lengths.size(); ++r) offsets[r] = offsets[r - 1] + lengths[r - 1];
    all.resize(size_t(offsets.back() + lengths.back()));
  }
  MPI_Igatherv(text.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0,
               MPI_COMM_WORLD, &request);
  waitSleeping(request);
  std::vector<std::string> out;
  for (size_t r = 0; r < lengths.size(); ++r)
    out.push_back(all.substr(size_t(offsets[r]), size_t(lengths[r])));
  return out;
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
