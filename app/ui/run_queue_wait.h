// How long the viewer's frame waited for a CPU while it was ready to run, from Linux's per-thread
// scheduler statistics (/proc/.../schedstat): the UI thread's own wait, plus the longest wait of Mesa's
// llvmpipe rasteriser threads, which the UI thread waits for in glFinish. The monkey test takes it out
// of a frame's time: on a loaded machine those threads wait for other processes, which says nothing
// about the viewer's code. Approximate (a rasteriser may wait while the UI thread is busy), and 0
// where the kernel does not report it.
#pragma once

#include <map>
#include <string>

namespace penumbra::ui {

class RunQueueWait {
 public:
  // Seconds waited since the previous call (the first call starts the count and returns 0).
  double sinceLast();

 private:
  bool started_ = false;
  double ui_ = 0;
  std::map<std::string, double> rasterisers_;  // thread id -> its total wait
};

}  // namespace penumbra::ui
