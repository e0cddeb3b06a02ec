// Threads that each run one body until it returns, at a chosen scheduling priority. No exception
// leaves a pool thread: one thrown by the body is handed to the pool's failure handler instead.
#pragma once

#include <exception>
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
  // Starts `count` threads running `body`; an exception escaping `body` is passed to `failed` (on
  // that thread; `failed` must not throw). Throws std::system_error when a thread cannot be started:
  // the threads already started keep running and must be stopped and joined by the caller.
  void spawn(int count, const std::function<void()>& body,
             const std::function<void(std::exception_ptr)>& failed);
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
