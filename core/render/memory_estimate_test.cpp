#include "core/render/memory_estimate.h"

#include <gtest/gtest.h>

#include <string>

#include "core/math/error.h"

namespace penumbra {
namespace {

TEST(MemoryEstimate, LargestCameraIsRefusedWithTheFigure) {
  EXPECT_EQ(estimateRenderBytes(16384, 16384), uint64_t(16384) * 16384 * kRenderBytesPerPixel);
  try {
    checkRenderFitsInMemory(16384, 16384, "scene.xml", uint64_t(8) << 30);
    FAIL() << "a 29 GB render was accepted with 8 GB available";
  } catch (const Error& e) {
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

}  // namespace
}  // namespace penumbra
