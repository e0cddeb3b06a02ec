// The process's MPI session (MPI_Init_thread .. MPI_Finalize) and the few collectives a shared
// render needs, over MPI_COMM_WORLD. Only the main thread calls MPI (MPI_THREAD_FUNNELED): the
// engine's workers never do.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace penumbra::mpi {

class Session {
 public:
  Session(int& argc, char**& argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  int ranksOnThisNode() const { return localSize_; }

  // Collectives: every rank must call them in the same order. The small ones sleep while they wait.
  int maxOf(int value) const;
  int sumOf(int value) const;
  void barrier() const;
  // Every rank's value, in rank order, on every rank.
  std::vector<uint64_t> allGather(uint64_t value) const;
  // Rank 0's `text` on every rank (other ranks' `text` is not used).
  std::string broadcastFromRoot(const std::string& text) const;
  // Every rank's `text`, in rank order, on rank 0; empty on the other ranks.
  std::vector<std::string> gatherToRoot(const std::string& text) const;
  // Element-wise sums onto rank 0 (MPI_Reduce, in chunks below MPI's int count; blocking: call it
  // after a barrier so that no rank waits in it). The first form sends `values` as they are and
  // writes the sums into rank 0's `total` (of the same size, allocated beforehand so that the
  // reduction touches no new memory); other ranks' `total` is not used. The second sums in place on
  // rank 0 and leaves other ranks' `values` unchanged.
  void sumToRoot(const std::vector<double>& values, std::vector<double>& total) const;
  void sumToRoot(std::vector<uint64_t>& values) const;
  double wallSeconds() const;  // MPI_Wtime
  // Ends every rank of the job (MPI_Abort) with `code`.
  [[noreturn]] void abort(int code) const;

 private:
  int rank_ = 0, size_ = 1, localSize_ = 1;
};

}  // namespace penumbra::mpi
