#include "app/cli/cpu_usage.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>

namespace penumbra::cli {
namespace {

TEST(CpuUsage, ShareOfCoresAndStealFromTwoReadings) {
  CpuClock before{10.0, 3.0, 100, 10000}, after{12.0, 6.0, 130, 10400};
  CpuShare s = cpuShareBetween(before, after, 2);
  EXPECT_DOUBLE_EQ(s.coresGot, 0.75);  // 3 CPU seconds in 2 s on 2 threads
  EXPECT_DOUBLE_EQ(s.steal, 30.0 / 400.0);
}

TEST(CpuUsage, NoHostTicksMeansStealUnknown) {
  CpuClock before{1.0, 0.0, 0, 0}, after{2.0, 1.0, 0, 0};
  CpuShare s = cpuShareBetween(before, after, 1);
  EXPECT_DOUBLE_EQ(s.coresGot, 1.0);
  EXPECT_LT(s.steal, 0.0);
  EXPECT_DOUBLE_EQ(cpuShareBetween(after, after, 1).coresGot, 0.0);  // no time passed: no division
}

TEST(CpuUsage, ReadingsAdvanceWithBusyWork) {
  const CpuClock a = readCpuClock();
  volatile double sink = 0;
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(50);
  while (std::chrono::steady_clock::now() < until) sink = sink + 1.0;
  const CpuClock b = readCpuClock();
  EXPECT_GT(b.wallSeconds, a.wallSeconds);
  EXPECT_GT(b.processSeconds, a.processSeconds);
  if (std::filesystem::exists("/proc/stat")) {
    EXPECT_GT(a.totalTicks, 0.0);
    EXPECT_GE(b.totalTicks, a.totalTicks);
    EXPECT_GE(b.stealTicks, a.stealTicks);
  }
}

}  // namespace
}  // namespace penumbra::cli
