#include "core/render/worker_pool.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace penumbra {

void WorkerPool::spawn(int count, const std::function<void()>& body,
                       const std::function<void(std::exception_ptr)>& failed) {
  count_ = count;
  const int nice = nice_;
  threads_.reserve(threads_.size() + count);
  for (int i = 0; i < count; ++i)
    threads_.emplace_back([nice, body, failed] {
      // Linux: a nice value set through the thread id applies to this thread only.
      if (nice > 0) setpriority(PRIO_PROCESS, id_t(syscall(SYS_gettid)), nice);
      try {
        body();
      } catch (...) {  // std::thread would call std::terminate
        failed(std::current_exception());
      }
    });
}

void WorkerPool::join() {
  for (std::thread& t : threads_) t.join();
  threads_.clear();
}

}  // namespace penumbra
