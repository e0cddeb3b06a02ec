#include "core/render/pass_barrier.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

namespace penumbra {
namespace {

// Every pass, exactly one of the workers does the boundary's work, and none starts the next pass
// before it is done.
TEST(PassBarrier, OneBoundaryPerPassAndNobodyRunsAhead) {
  constexpr int kWorkers = 4, kPasses = 200;
  PassBarrier barrier;
  barrier.reset(kWorkers);
  int boundaries = 0;  // written by the boundary only, under the lock
  std::atomic<int> errors{0};
  std::vector<std::thread> workers;
  for (int w = 0; w < kWorkers; ++w)
    workers.emplace_back([&] {
      for (int pass = 0; pass < kPasses; ++pass) {
        PassBarrier::Lock lk = barrier.lock();
        if (barrier.arrive(lk)) {
          if (boundaries != pass) ++errors;
          ++boundaries;
          barrier.release();
        }
        if (boundaries != pass + 1) ++errors;  // read under the lock
      }
    });
  for (std::thread& t : workers) t.join();
  EXPECT_EQ(boundaries, kPasses);
  EXPECT_EQ(errors.load(), 0);
}

}  // namespace
}  // namespace penumbra
