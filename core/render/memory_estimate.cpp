#include "core/render/memory_estimate.h"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace penumbra {

namespace {

// The value in kB of the line "<key>: N kB" of a /proc file, in bytes (0 if absent).
uint64_t procField(const char* path, const std::string& key) {
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(key, 0) != 0 || line.size() <= key.size() || line[key.size()] != ':') continue;
    std::istringstream value(line.substr(key.size() + 1));
    uint64_t kb = 0;
    return value >> kb ? kb * 1024 : 0;
  }
  return 0;
}

}  // namespace

uint64_t estimateRenderBytes(int width, int height) {
  return uint64_t(std::max(width, 0)) * uint64_t(std::max(height, 0)) * kRenderBytesPerPixel;
}

uint64_t availableMemoryBytes() {
  uint64_t available = procField("/proc/meminfo", "MemAvailable");
  // A limit counts what the process already has (an interpreter and its libraries, thread stacks).
  const std::pair<int, const char*> limits[] = {{RLIMIT_AS, "VmSize"}, {RLIMIT_DATA, "VmData"}};
  for (auto [resource, inUse] : limits) {
    rlimit r;
    if (getrlimit(resource, &r) != 0 || r.rlim_cur == RLIM_INFINITY) continue;
    const uint64_t used = procField("/proc/self/status", inUse);
    const uint64_t left = uint64_t(r.rlim_cur) > used ? uint64_t(r.rlim_cur) - used : 1;
    available = available == 0 ? left : std::min(available, left);
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
  throw OutOfMemoryError(what + ": a " + std::to_string(width) + "x" + std::to_string(height) +
                         " render needs about " + formatBytes(needed) + " (" +
                         std::to_string(kRenderBytesPerPixel) + " B/pixel), only " + formatBytes(available) +
                         " available; lower camera width/height");
}

void checkFitsInMemory(uint64_t bytes, const std::string& what, uint64_t available) {
  if (available == 0) available = availableMemoryBytes();
  if (available == 0 || bytes <= available) return;
  throw OutOfMemoryError(what + " needs about " + formatBytes(bytes) + ", only " + formatBytes(available) +
                         " available");
}

}  // namespace penumbra
