// Where the render workers meet at the end of every pass: the last to arrive runs the boundary's work
// while the others wait. Its mutex also guards the engine's pass state (limits, pause, the film at
// rest), and its condition variable wakes a boundary that waits while the render is paused.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <mutex>

namespace penumbra {

class PassBarrier {
 public:
  using Lock = std::unique_lock<std::mutex>;

  // Expects `parties` arrivals per pass; only while no worker runs.
  void reset(int parties) {
    parties_ = parties;
    arrived_ = 0;
  }
  Lock lock() const { return Lock(mutex_); }

  // Under `lk`. Returns true to the last to arrive, which does the boundary's work and then calls
  // release(); the others wait until it has (or until `giveUp()` holds) and return false.
  template <class GiveUp>
  bool arrive(Lock& lk, GiveUp giveUp) {
    const uint64_t generation = generation_;
    if (++arrived_ == parties_) {
      arrived_ = 0;
      return true;
    }
    cv_.wait(lk, [&] { return generation_ != generation || giveUp(); });
    return false;
  }
  bool arrive(Lock& lk) {
    return arrive(lk, [] { return false; });
  }
  // Under the lock: the boundary is over, the waiting workers go on.
  void release() {
    ++generation_;
    cv_.notify_all();
  }

  // For the boundary's own waits (pause) and whoever ends them.
  template <class Pred>
  void wait(Lock& lk, Pred done) {
    cv_.wait(lk, done);
  }
  void notifyAll() { cv_.notify_all(); }

 private:
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  int parties_ = 0;
  int arrived_ = 0;
  uint64_t generation_ = 0;
};

}  // namespace penumbra
