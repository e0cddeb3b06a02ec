#include "core/render/memory_estimate.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include "core/math/error.h"

namespace penumbra {
namespace {

TEST(MemoryEstimate, LargestCameraIsRefusedWithTheFigure) {
  EXPECT_EQ(estimateRenderBytes(16384, 16384), uint64_t(16384) * 16384 * kRenderBytesPerPixel);
  try {
    checkRenderFitsInMemory(16384, 16384, "scene.xml", uint64_t(8) << 30);
    FAIL() << "a 29 GB render was accepted with 8 GB available";
  } catch (const OutOfMemoryError& e) {  // an Error: the CLI exits with 2
    const std::string m = e.what();
    EXPECT_NE(m.find("16384x16384"), std::string::npos) << m;
    EXPECT_NE(m.find("27.0 GB"), std::string::npos) << m;
    EXPECT_NE(m.find("8.0 GB available"), std::string::npos) << m;
  }
}

TEST(MemoryEstimate, OrdinaryRendersFit) {
  EXPECT_NO_THROW(checkRenderFitsInMemory(1280, 720, "scene.xml", uint64_t(1) << 30));
  EXPECT_GT(availableMemoryBytes(), 0u);
}

TEST(MemoryEstimate, OtherAllocationsAreCheckedTheSameWay) {
  EXPECT_NO_THROW(checkFitsInMemory(uint64_t(1) << 20, "warp output", uint64_t(1) << 30));
  try {
    checkFitsInMemory(uint64_t(3) << 30, "warp output", uint64_t(1) << 30);
    FAIL() << "3 GB accepted with 1 GB available";
  } catch (const OutOfMemoryError& e) {
    EXPECT_STREQ(e.what(), "warp output needs about 3.0 GB, only 1.0 GB available");
  }
}

// The address space a process already uses counts against RLIMIT_AS (a Python interpreter holds
// hundreds of MB before it renders anything).
TEST(MemoryEstimate, AnAddressSpaceLimitCountsWhatIsAlreadyMapped) {
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {  // the limit would hold for the whole test binary: set it in a child
    uint64_t vmSize = 0;
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
      if (line.rfind("VmSize:", 0) == 0) vmSize = std::stoull(line.substr(7)) * 1024;
    const uint64_t headroom = uint64_t(64) << 20;
    rlimit limit{rlim_t(vmSize + headroom), RLIM_INFINITY};
    if (vmSize == 0 || setrlimit(RLIMIT_AS, &limit) != 0) _exit(3);
    const uint64_t available = availableMemoryBytes();
    _exit(available > 0 && available <= headroom ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "1: the available memory ignored what is mapped; 3: no limit set";
}

}  // namespace
}  // namespace penumbra
