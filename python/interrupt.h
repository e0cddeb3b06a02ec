// Long calls stay interruptible: the work runs with the GIL released while the calling thread checks
// for signals at least every 20 ms (PyErr_CheckSignals: Ctrl-C's KeyboardInterrupt, or whatever a
// Python signal handler raises). On such an exception the work is cancelled, waited for (it stops
// within a fraction of a second), and the exception is raised.
#pragma once

#include <pybind11/pybind11.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <future>
#include <thread>
#include <type_traits>

#include "core/math/cancellation.h"

namespace penumbra::python {

namespace py = pybind11;

inline constexpr std::chrono::milliseconds kSignalPoll{20};

// Raises the exception of a signal handler, if one ran (needs the GIL).
inline void raiseIfSignalled() {
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
}

// Runs work(CancelFlag) on a helper thread; returns its result or rethrows its exception here. The
// work must not touch Python objects. Call with the GIL held.
template <class F>
auto runInterruptibly(F&& work) -> std::invoke_result_t<F&, CancelFlag> {
  using Result = std::invoke_result_t<F&, CancelFlag>;
  std::atomic<bool> cancel{false};
  std::packaged_task<Result()> task([&] { return work(&cancel); });
  std::future<Result> result = task.get_future();
  std::thread worker;
  {
    py::gil_scoped_release release;
    worker = std::thread(std::move(task));
  }
  // Whatever leaves this function, the worker is stopped and joined first (it uses our locals).
  struct Joiner {
    std::thread& worker;
    std::atomic<bool>& cancel;
    ~Joiner() {
      cancel = true;
      py::gil_scoped_release release;
      worker.join();
    }
  } joiner{worker, cancel};
  for (;;) {
    bool ready;
    {
      py::gil_scoped_release release;
      ready = result.wait_for(kSignalPoll) == std::future_status::ready;
    }
    if (ready) break;
    raiseIfSignalled();  // the joiner cancels the work; its Cancelled stays in the dropped future
  }
  return result.get();
}

// body(begin, end) over [0, n) in chunks of `chunk`, each with the GIL released, checking for
// signals between chunks. Call with the GIL held.
template <class F>
void forEachChunk(int64_t n, int64_t chunk, F&& body) {
  for (int64_t begin = 0; begin < n; begin += chunk) {
    const int64_t end = std::min(n, begin + chunk);
    {
      py::gil_scoped_release release;
      body(begin, end);
    }
    raiseIfSignalled();
  }
}

}  // namespace penumbra::python
