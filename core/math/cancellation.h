// Stopping long computations that run outside the engine (chi-square tests, convergence runs,
// references) from another thread: the caller owns an atomic flag and sets it; the computation
// checks it often enough to stop within a fraction of a second and throws Cancelled.
#pragma once

#include <atomic>
#include <exception>

namespace penumbra {

// Thrown by a computation whose cancel flag was set; it leaves nothing half-written behind.
class Cancelled : public std::exception {
 public:
  const char* what() const noexcept override { return "cancelled"; }
};

// The flag a computation checks; null: it cannot be cancelled.
using CancelFlag = const std::atomic<bool>*;

inline bool cancelRequested(CancelFlag flag) {
  return flag && flag->load(std::memory_order_relaxed);
}

inline void throwIfCancelled(CancelFlag flag) {
  if (cancelRequested(flag)) throw Cancelled();
}

}  // namespace penumbra
