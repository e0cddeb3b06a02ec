// CPU time consumed so far, in seconds: unlike wall time it does not grow while other processes hold
// the cores, so rates per CPU second are stable on a shared machine.
#pragma once

#include <ctime>

namespace penumbra {

inline double cpuClockSeconds(clockid_t clock) {
  timespec ts;
  clock_gettime(clock, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// All of this process's threads.
inline double processCpuSeconds() {
  return cpuClockSeconds(CLOCK_PROCESS_CPUTIME_ID);
}

// The calling thread alone.
inline double threadCpuSeconds() {
  return cpuClockSeconds(CLOCK_THREAD_CPUTIME_ID);
}

}  // namespace penumbra
