// End-to-end tests of numeric arguments at the edges of their types: each must be rejected with exit
// code 2 at once (never wrap, saturate, become NaN or inf, or round into a different value), or be
// used exactly as given. `timeout` turns a hang into a failure instead of a stuck suite.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "tests/run_command.h"

namespace {

using penumbra::test::CommandResult;

const std::string kScene = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/hw2/Tests/sphere-area.xml";

CommandResult penumbra(const std::string& args) {
  return penumbra::test::runCommand("timeout -s KILL 120 '" PENUMBRA_BINARY "' " + args);
}

// Standard output is discarded: a command that wrongly accepts "--dump -1" writes without end.
void expectRejected(const std::string& args, const std::string& text = "") {
  CommandResult r =
      penumbra::test::runCommand("(timeout -s KILL 120 '" PENUMBRA_BINARY "' " + args + " >/dev/null)");
  EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.out;
  if (!text.empty()) {
    EXPECT_NE(r.out.find(text), std::string::npos) << args << "\n" << r.out;
  }
}

TEST(CliArguments, WarpParametersBeyondFloatRangeAreRejectedNotIntegratedForever) {
  expectRejected("warp beckmann --param 1e300", "beckmann");
  expectRejected("warp beckmann --param 3.5e38", "beckmann");
  expectRejected("warp beckmann --param 1e300 --dump 3");
  expectRejected("warp beckmann --param inf");
  expectRejected("warp beckmann --param nan");
}

TEST(CliArguments, WarpParametersAreValidatedAsTheFloatTheWarpUses) {
  // 0.99999999999 < 1 as a double, but 1.0 as a float: a degenerate cone.
  expectRejected("warp uniform-cone --param 0.99999999999", "rounds to 1");
  expectRejected("warp beckmann --param 1e-30", "beckmann");
  // The largest float below 1 is a valid cone, and the test accepts it.
  CommandResult r = penumbra("warp uniform-cone --param 0.99999994 --samples 100000");
  EXPECT_EQ(r.exitCode, 0) << r.out;
}

TEST(CliArguments, CountsAndSeedsDoNotWrapOrSaturate) {
  expectRejected("warp uniform-square --dump -1", "non-negative integer");
  expectRejected("warp uniform-square --dump 18446744073709551616", "out of range");
  expectRejected("warp uniform-square --dump 1e3");
  expectRejected("warp uniform-square --seed -1", "non-negative integer");
  expectRejected("warp uniform-square --seed 18446744073709551616", "out of range");
  expectRejected("warp uniform-square --samples -1");
  CommandResult r = penumbra("warp uniform-square --dump 3 --seed 18446744073709551615");
  EXPECT_EQ(r.exitCode, 0) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 3) << r.out;
}

TEST(CliArguments, TimesMustBeFinitePositiveNumbers) {
  for (const char* t : {"nan", "inf", "-1", "0", "1x"}) {
    expectRejected("render " + kScene + " --time " + t + " -o unused.pfm", "--time");
    expectRejected("converge " + kScene + " --time " + t + " -o unused-dir", "--time");
  }
}

}  // namespace
