#include "app/ui/run_queue_wait.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace penumbra::ui {

namespace {

// The second field of a schedstat file: nanoseconds spent runnable but not running.
double waitSeconds(const std::string& schedstat) {
  std::FILE* f = std::fopen(schedstat.c_str(), "r");
  if (!f) return -1;
  unsigned long long running = 0, waiting = 0;
  const int n = std::fscanf(f, "%llu %llu", &running, &waiting);
  std::fclose(f);
  return n == 2 ? double(waiting) * 1e-9 : -1;
}

}  // namespace

double RunQueueWait::sinceLast() {
  const double ui = std::max(waitSeconds("/proc/thread-self/schedstat"), 0.0);
  double longest = 0;
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    std::string name;
    std::getline(std::ifstream(task.path() / "comm"), name);
    if (name.rfind("llvmpipe-", 0) != 0) continue;
    const double w = waitSeconds((task.path() / "schedstat").string());
    if (w < 0) continue;
    auto [it, fresh] = rasterisers_.emplace(task.path().filename().string(), w);
    if (!fresh) longest = std::max(longest, w - it->second);
    it->second = w;
  }
  const double waited = started_ ? (ui - ui_) + longest : 0;
  started_ = true;
  ui_ = ui;
  return waited;
}

}  // namespace penumbra::ui
