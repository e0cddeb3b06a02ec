// End-to-end tests of numeric arguments at the edges of their types: each must be rejected with exit
// code 2 at once (never wrap, saturate, become NaN or inf, or round into a different value), or be
// used exactly as given. `timeout` turns a hang into a failure instead of a stuck suite.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

#include "core/image/image_io.h"
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

// Every command's --seed takes exactly the 64-bit unsigned integers; nothing is clamped into range.
TEST(CliArguments, SeedsBeyond64BitsAreRejectedByEveryCommand) {
  for (const std::string& command :
       {"render " + kScene + " --spp 1 -o unused.pfm", "converge " + kScene + " --spp 1 -o unused-dir",
        std::string("warp uniform-square"), std::string("check --quick")}) {
    expectRejected(command + " --seed 18446744073709551616",
                   "--seed: '18446744073709551616' is out of range");
    expectRejected(command + " --seed -1", "non-negative integer");
    expectRejected(command + " --seed 1e3", "non-negative integer");
  }
}

TEST(CliArguments, RenderTakesTheLargestSeedAsGiven) {
  const std::string out = "/tmp/penumbra-seed-" + std::to_string(::getpid()) + ".exr";
  CommandResult r =
      penumbra("render " + kScene +
               " --set camera.width=8 --set camera.height=8 --spp 1 --seed 18446744073709551615 -o " + out);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const penumbra::ImageMetadata meta = penumbra::readImageMetadata(out);
  ASSERT_NE(meta.find("seed"), nullptr);
  EXPECT_EQ(*meta.find("seed"), "18446744073709551615");
  std::remove(out.c_str());
}

TEST(CliArguments, EmptyDisplayServerIsRejected) {
  // Small, and written under /tmp, should a command accept it.
  const std::string tmp = "/tmp/penumbra-empty-display-" + std::to_string(::getpid());
  const std::string small = " --set camera.width=8 --set camera.height=8 --spp 1 --display-server '' ";
  expectRejected("render " + kScene + small + "-o " + tmp + ".pfm",
                 "--display-server: expected HOST or HOST:PORT");
  expectRejected(
      "converge " + kScene + small + "--strategies area --reference-spp 1 --cache-dir " + tmp + " -o " + tmp,
      "--display-server");
  CommandResult view = penumbra::test::runCommand("timeout -s KILL 120 '" PENUMBRA_OFFSCREEN_BINARY
                                                  "' view /nonexistent.xml --frames 1 --display-server ''");
  EXPECT_EQ(view.exitCode, 2) << view.out;
  EXPECT_NE(view.out.find("--display-server: expected HOST or HOST:PORT"), std::string::npos) << view.out;
  penumbra::test::runCommand("rm -rf " + tmp + " " + tmp + ".pfm");
}

TEST(CliArguments, BenchOptionsThatContradictOrExceedTheSceneLimitAreNamed) {
  expectRejected("bench --scaling-only --scaling-spp 0", "--scaling-spp 0 skips the scaling series");
  const std::string out = "/tmp/penumbra-scaling-" + std::to_string(::getpid()) + ".xml";
  expectRejected("bench --write-scaling-scene " + out + " --lights 200000",
                 "above the 64 MB that penumbra reads");
  CommandResult exists = penumbra::test::runCommand("test -e " + out);
  EXPECT_NE(exists.exitCode, 0) << "nothing written";
}

TEST(CliArguments, SceneFileWithANulCharacterIsRefusedWithItsLine) {
  const std::string scene = "/tmp/penumbra-nul-" + std::to_string(::getpid()) + ".xml";
  {
    std::ofstream f(scene, std::ios::binary);
    f << "<scene>\n  <shape type=\"sphere\"/>\n";
    f.put('\0');
    f << "\n</scene>\n";
  }
  expectRejected("render " + scene + " --spp 1 -o unused.pfm",
                 scene + ":3: column 1: a NUL character (byte 0) is not allowed");
  std::remove(scene.c_str());
}

}  // namespace
