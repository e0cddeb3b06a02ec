// End-to-end tests of `penumbra warp`: runs the built binary and checks exit codes and output.
#include <gtest/gtest.h>

#include "core/math/vec.h"
#include "tests/run_command.h"

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

namespace {

using CliRun = penumbra::test::CommandResult;
using penumbra::kPiD;

// Runs `penumbra <args>` through the shell (stderr merged into the output).
CliRun penumbra(const std::string& args, const std::string& prefix = "") {
  return penumbra::test::runCommand(prefix + "'" PENUMBRA_BINARY "' " + args);
}

TEST(WarpCli, AcceptsConsistentWarp) {
  CliRun r = penumbra("warp cosine-hemisphere --samples 200000 --seed 4");
  EXPECT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.out.find("accept"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("p-value"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("dof"), std::string::npos) << r.out;
}

TEST(WarpCli, ParameterisedWarps) {
  EXPECT_EQ(penumbra("warp uniform-cone --param 0.9 --samples 200000").exitCode, 0);
  EXPECT_EQ(penumbra("warp beckmann --param 0.3 --samples 200000 --res 31").exitCode, 0);
}

TEST(WarpCli, RejectsMismatchedPairs) {
  CliRun r = penumbra("warp cosine-hemisphere --pdf-of uniform-hemisphere --samples 200000");
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_NE(r.out.find("REJECT"), std::string::npos) << r.out;
  EXPECT_EQ(penumbra("warp cosine-hemisphere --mismatch --samples 200000").exitCode, 1);
  EXPECT_EQ(penumbra("warp uniform-sphere --pdf-scale 2 --samples 200000").exitCode, 1);
}

// Too few samples for the grid (every cell pooled into one): nothing to test, so the verdict is
// inconclusive, not REJECT, and the exit code 1 of any test that does not accept.
TEST(WarpCli, TooFewSamplesAreInconclusiveWithExitCodeOne) {
  CliRun r = penumbra("warp cosine-hemisphere --samples 100");
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_NE(r.out.find("verdict   inconclusive"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("REJECT"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("dof       0"), std::string::npos) << r.out;
  CliRun help = penumbra("warp --help");
  EXPECT_NE(help.out.find("1 REJECT, or inconclusive"), std::string::npos) << help.out;
}

TEST(WarpCli, BadArgumentsExitWithTwo) {
  CliRun r = penumbra("warp no-such-warp");
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("unknown warp type"), std::string::npos) << r.out;
  r = penumbra("warp uniform-cone --param 1.5");
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("[-1, 1)"), std::string::npos) << r.out;
  r = penumbra("warp beckmann --param 0");
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("alpha"), std::string::npos) << r.out;
  EXPECT_EQ(penumbra("warp beckmann --param=-1").exitCode, 2);
  EXPECT_EQ(penumbra("warp tent --param 0.3").exitCode, 2);
  EXPECT_EQ(penumbra("warp").exitCode, 2);
  EXPECT_EQ(penumbra("warp tent --samples banana").exitCode, 2);
  EXPECT_EQ(penumbra("warp tent --all").exitCode, 2);
}

TEST(WarpCli, DumpThenPdfRoundTrip) {
  CliRun dump = penumbra("warp uniform-sphere --dump 50 --seed 9");
  ASSERT_EQ(dump.exitCode, 0) << dump.out;
  std::istringstream in(dump.out);
  int lines = 0;
  double x, y, z;
  while (in >> x >> y >> z) {
    EXPECT_NEAR(std::sqrt(x * x + y * y + z * z), 1.0, 1e-6);
    ++lines;
  }
  EXPECT_EQ(lines, 50);

  CliRun pdf = penumbra("warp cosine-hemisphere --pdf", "printf '0 0 1\\n0.6 0 0.8\\n0 0 -1\\n' | ");
  ASSERT_EQ(pdf.exitCode, 0) << pdf.out;
  std::istringstream pin(pdf.out);
  double a, b, c;
  ASSERT_TRUE(pin >> a >> b >> c) << pdf.out;
  EXPECT_NEAR(a, 1.0 / kPiD, 1e-7);
  EXPECT_NEAR(b, 0.8 / kPiD, 1e-7);
  EXPECT_EQ(c, 0.0);

  CliRun piped = penumbra("warp uniform-cone --param 0.5 --pdf",
                          "'" PENUMBRA_BINARY "' warp uniform-cone --param 0.5 --dump 20 | ");
  ASSERT_EQ(piped.exitCode, 0) << piped.out;
  std::istringstream qin(piped.out);
  int count = 0;
  while (qin >> a) {
    EXPECT_NEAR(a, 1.0 / (2 * kPiD * 0.5), 1e-6);
    ++count;
  }
  EXPECT_EQ(count, 20);

  EXPECT_EQ(penumbra("warp tent --pdf", "echo 'not numbers' | ").exitCode, 2);
}

TEST(WarpCli, AllAcceptsEverything) {
  CliRun r = penumbra("warp --all --samples 100000 --res 25");
  EXPECT_EQ(r.exitCode, 0) << r.out;
  EXPECT_EQ(r.out.find("REJECT"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("beckmann"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Sidak"), std::string::npos) << r.out;
}

}  // namespace
