#include "app/cli/cpu_usage.h"

#include <chrono>
#include <fstream>
#include <string>

#include "core/render/cpu_clock.h"

namespace penumbra::cli {

CpuClock readCpuClock() {
  CpuClock c;
  c.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  c.processSeconds = processCpuSeconds();
  // First line: "cpu  user nice system idle iowait irq softirq steal guest guest_nice" (guest time is
  // already counted in user and nice, so it is not added again).
  std::ifstream stat("/proc/stat");
  std::string label;
  double field[8];
  if (stat >> label && label == "cpu") {
    int n = 0;
    while (n < 8 && stat >> field[n]) ++n;
    if (n == 8) {
      for (double f : field) c.totalTicks += f;
      c.stealTicks = field[7];
    }
  }
  return c;
}

CpuShare cpuShareBetween(const CpuClock& before, const CpuClock& after, int threads) {
  CpuShare s;
  const double wall = after.wallSeconds - before.wallSeconds;
  if (wall > 0 && threads > 0) s.coresGot = (after.processSeconds - before.processSeconds) / (wall * threads);
  const double total = after.totalTicks - before.totalTicks;
  if (total > 0) s.steal = (after.stealTicks - before.stealTicks) / total;
  return s;
}

}  // namespace penumbra::cli
