// How long the calling thread has waited for a CPU while it was ready to run (Linux's per-thread
// scheduler statistics). The monkey test takes it out of a frame's time: on a loaded machine the UI
// thread waits for other processes' threads, which says nothing about the viewer's code.
#pragma once

#include <cstdio>

namespace penumbra::ui {

// Seconds this thread spent runnable but not running, or 0 where the kernel does not say.
inline double runQueueWaitSeconds() {
  std::FILE* f = std::fopen("/proc/thread-self/schedstat", "r");
  if (!f) return 0;
  unsigned long long running = 0, waiting = 0;
  const int n = std::fscanf(f, "%llu %llu", &running, &waiting);
  std::fclose(f);
  return n == 2 ? double(waiting) * 1e-9 : 0;
}

}  // namespace penumbra::ui
