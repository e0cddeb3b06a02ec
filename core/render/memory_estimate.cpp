#include "core/render/memory_estimate.h"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/math/error.h"

namespace penumbra {

uint64_t estimateRenderBytes(int width, int height) {
  return uint64_t(std::max(width, 0)) * uint64_t(std::max(height, 0)) * kRenderBytesPerPixel;
}

uint64_t availableMemoryBytes() {
  uint64_t available = 0;
  std::ifstream meminfo("/proc/meminfo");
  for (std::string line; std::getline(meminfo, line);) {
    if (line.rfind("MemAvailable:", 0) != 0) continue;
    std::istringstream in(line.substr(13));
    uint64_t kb = 0;
    if (in >> kb) available = kb * 1024;
    break;
  }
  for (int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    rlimit r;
    if (getrlimit(resource, &r) == 0 && r.rlim_cur != RLIM_INFINITY)
      available = available == 0 ? uint64_t(r.rlim_cur) : std::min(available, uint64_t(r.rlim_cur));
  }
  return available;
}

std::string formatBytes(uint64_t bytes) {
  char buf[32];
  if (bytes >= (uint64_t(1) << 30))
    std::snprintf(buf, sizeof buf, "%.1f GB", double(bytes) / double(uint64_t(1) << 30));
  else
    std::snprintf(buf, sizeof buf, "%.0f MB", double(bytes) / double(1 << 20));
  return buf;
}

void checkRenderFitsInMemory(int width, int height, const std::string& what, uint64_t available) {
  if (available == 0) available = availableMemoryBytes();
  const uint64_t needed = estimateRenderBytes(width, height);
  if (available == 0 || needed <= available) return;
  throw Error(what + ": a " + std::to_string(width) + "x" + std::to_string(height) + " render needs about " +
              formatBytes(needed) + " (" + std::to_string(kRenderBytesPerPixel) + " B/pixel), only " +
              formatBytes(available) + " available; lower camera width/height");
}

}  // namespace penumbra
