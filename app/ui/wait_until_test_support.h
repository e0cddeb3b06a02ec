// Polling until a condition holds, for the viewer's tests of its render threads.
#pragma once

#include <chrono>
#include <thread>

namespace penumbra::test {

// Polls `done` every 2 ms; false when it still does not hold after `limit`.
template <class F>
bool waitUntil(F done, std::chrono::seconds limit = std::chrono::seconds(30)) {
  const auto t0 = std::chrono::steady_clock::now();
  while (!done()) {
    if (std::chrono::steady_clock::now() - t0 > limit) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

}  // namespace penumbra::test
