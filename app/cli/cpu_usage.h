// What the machine did with its CPUs while a benchmark ran, so that a slow figure can be told from a
// contended one: this process's CPU time (did our threads get their cores?) and, on Linux, the
// host's steal time from /proc/stat (did the hypervisor give the virtual CPUs to someone else?).
#pragma once

namespace penumbra::cli {

struct CpuClock {
  double wallSeconds = 0;     // steady clock
  double processSeconds = 0;  // CPU time of all this process's threads
  double stealTicks = 0;      // /proc/stat, all CPUs; 0 where unavailable
  double totalTicks = 0;      // /proc/stat, all CPUs, every state; 0 where unavailable
};

CpuClock readCpuClock();

struct CpuShare {
  // Process CPU time over (wall time × threads): 1 when every thread ran all the time.
  double coresGot = 0;
  // Host steal time over all CPU time, or < 0 where /proc/stat is unavailable.
  double steal = -1;
};

// Between two readings, for a process that kept `threads` threads busy.
CpuShare cpuShareBetween(const CpuClock& before, const CpuClock& after, int threads);

}  // namespace penumbra::cli
