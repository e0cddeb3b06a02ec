// Threads that each run one body until it returns, at a chosen scheduling priority.
#pragma once

#include <functional>
#include <thread>
#include <vector>

namespace penumbra {

class WorkerPool {
 public:
  WorkerPool() = default;
  ~WorkerPool() { join(); }
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  // Linux nice value (0..19) of the threads of later spawn() calls. An interactive viewer raises it
  // so that its UI thread gets a core at once instead of a fair share beside the workers.
  void setNice(int nice) { nice_ = nice; }
  // Starts `count` threads running `body`.
  void spawn(int count, const std::function<void()>& body);
  // Waits for every thread to return.
  void join();
  // Threads of the last spawn().
  int size() const { return count_; }

 private:
  std::vector<std::thread> threads_;
  int count_ = 0;
  int nice_ = 0;
};

}  // namespace penumbra
