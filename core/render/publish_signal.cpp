#include "core/render/publish_signal.h"

#include <chrono>

namespace penumbra {

void PublishSignal::notify() {
  {
    std::lock_guard lk(mutex_);
    ++count_;
  }
  cv_.notify_all();
}

uint64_t PublishSignal::count() const {
  std::lock_guard lk(mutex_);
  return count_;
}

uint64_t PublishSignal::wait(uint64_t seen, double seconds) const {
  std::unique_lock lk(mutex_);
  cv_.wait_for(lk, std::chrono::duration<double>(seconds), [&] { return count_ != seen; });
  return count_;
}

}  // namespace penumbra
