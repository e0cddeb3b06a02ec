// Counts snapshot publications, so a viewer can sleep until one of its engines has something new
// (Engine::setPublishSignal) instead of polling.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <mutex>

namespace penumbra {

class PublishSignal {
 public:
  void notify();
  uint64_t count() const;
  // Waits until count() differs from `seen`, or `seconds` pass; returns count().
  uint64_t wait(uint64_t seen, double seconds) const;

 private:
  mutable std::mutex mutex_;
  mutable std::condition_variable cv_;
  uint64_t count_ = 0;
};

}  // namespace penumbra
