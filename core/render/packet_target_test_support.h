// For tests that run the packet kernels on one instruction set: forces it for the test's scope.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "core/render/packet_kernels.h"

namespace penumbra::test {

// Forces the instruction set `name` (one of availablePacketTargets()) until it goes out of scope, then
// restores the best one.
struct ForcedTarget {
  explicit ForcedTarget(const std::string& name) { EXPECT_TRUE(forcePacketTarget(name)) << name; }
  ~ForcedTarget() { forcePacketTarget("auto"); }
};

}  // namespace penumbra::test
