// End-to-end tests of `penumbra render` against hostile outputs, inputs and interrupts: everything
// that can be checked is checked before the first sample; Ctrl-C stops within a pixel and writes the
// completed passes with exit code 130.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/image/image_io.h"
#include "core/math/temp_dir_test_support.h"
#include "core/render/memory_estimate.h"
#include "tests/run_command.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using test::CommandResult;

const std::string kScene = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/hw2/Tests/sphere-area.xml";
const std::string kBinary = PENUMBRA_BINARY;

class RenderCli : public test::TempDirTest {
 protected:
  RenderCli() : TempDirTest("penumbra-render-cli-") {}
  // `penumbra render` with a hard time limit: a render that ignores what it was told fails the test
  // (exit -1 or 137) instead of hanging the suite.
  CommandResult render(const std::string& args, int limitSeconds = 120) {
    return test::runCommand("timeout -s KILL " + std::to_string(limitSeconds) + " '" + kBinary + "' render " +
                            args);
  }
  // Starts a render in the background, waits `afterSeconds`, sends SIGINT `interrupts` times and
  // reports the render's exit code as "rc=N" on the last line.
  CommandResult interrupted(const std::string& args, int interrupts = 1, double afterSeconds = 2) {
    std::string kills;
    for (int i = 0; i < interrupts; ++i) kills += "kill -INT $pid; ";
    return test::runCommand("'" + kBinary + "' render " + args + " 2>&1 & pid=$!; sleep " +
                            std::to_string(afterSeconds) + "; " + kills +
                            "( sleep 60; kill -KILL $pid ) >/dev/null 2>&1 & guard=$!; wait $pid; rc=$?; "
                            "kill $guard 2>/dev/null; echo rc=$rc");
  }
};

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST_F(RenderCli, UnwritableOutputsAreRefusedBeforeRendering) {
  fs::create_directories(dir / "adir.exr");
  // --time 600: a render that checks the output only afterwards runs into the 60 s limit.
  for (const std::string& out : {file("out.xyz"), file("noextension"), file("missing/out.exr"),
                                 file("adir.exr"), std::string("/proc/penumbra-render-test.exr")}) {
    CommandResult r = render(kScene + " --time 600 -o " + out, 60);
    EXPECT_EQ(r.exitCode, 2) << out << "\n" << r.out;
    EXPECT_NE(r.out.find("error:"), std::string::npos) << r.out;
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);  // adir.exr only
}

TEST_F(RenderCli, ReadOnlyOutputIsRefusedAndLeftAsItWas) {
  const std::string out = file("ro.pfm");
  ASSERT_EQ(render(kScene + " --spp 1 --set camera.width=8 --set camera.height=8 -o " + out).exitCode, 0);
  const std::string before = readBytes(out);
  fs::permissions(out, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  CommandResult r = render(kScene + " --spp 2 --set camera.width=8 --set camera.height=8 -o " + out);
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("read-only"), std::string::npos) << r.out;
  EXPECT_EQ(readBytes(out), before);
  struct stat st;
  ASSERT_EQ(::stat(out.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0444u);
}

TEST_F(RenderCli, ScenePathsAndMeshPathsThatAreNotRegularFilesAreRefused) {
  CommandResult r = render(dir.string() + " --spp 1 -o " + file("a.pfm"));
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("is a directory"), std::string::npos) << r.out;
  std::ofstream(file("zero.xml"))
      << "<scene><shape type=\"obj\"><string name=\"filename\" value=\"/dev/zero\"/>"
         "</shape></scene>";
  // A reader of /dev/zero would read until memory runs out; 60 s is far more than refusing takes.
  r = render(file("zero.xml") + " --spp 1 -o " + file("a.pfm"), 60);
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("not a regular file"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(file("a.pfm")));
}

TEST_F(RenderCli, RendersTooLargeForMemoryAreRefusedWithTheFigure) {
  if (availableMemoryBytes() >= estimateRenderBytes(16384, 16384))
    GTEST_SKIP() << "this machine has room for a 16384^2 render";
  CommandResult r = render(
      kScene + " --spp 1 --set camera.width=16384 --set camera.height=16384 -o " + file("big.exr"), 60);
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("16384x16384 render needs about 27.0 GB"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(file("big.exr")));
}

TEST_F(RenderCli, InterruptWritesTheCompletedPassesAndExits130) {
  const std::string out = file("partial.exr");
  const std::string small = kScene + " --set camera.width=32 --set camera.height=24 --threads 2";
  CommandResult r = interrupted(small + " --time 600 -o " + out);
  EXPECT_NE(r.out.find("rc=130"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("interrupted"), std::string::npos) << r.out;
  ASSERT_TRUE(fs::exists(out)) << r.out;
  ImageMetadata meta = readImageMetadata(out);
  ASSERT_NE(meta.find("interrupted"), nullptr);
  EXPECT_EQ(*meta.find("interrupted"), "true");
  ASSERT_NE(meta.find("spp"), nullptr);
  const std::string spp = *meta.find("spp");
  EXPECT_NE(spp, "0");
  // Whole passes only: the image equals a complete render of that many passes.
  const std::string whole = file("whole.exr");
  CommandResult full = render(small + " --spp " + spp + " -o " + whole, 600);
  ASSERT_EQ(full.exitCode, 0) << full.out;
  EXPECT_EQ(readImage(out).rgb, readImage(whole).rgb);
  EXPECT_EQ(*readImageMetadata(whole).find("interrupted"), "false");
}

TEST_F(RenderCli, InterruptStopsInsideALongPassAndWritesNothingWithoutAWholePass) {
  // 65536 light samples per pixel at 128x128: one pass takes minutes. Two interrupts in a row: the
  // render stops at once either way (the second may arrive while the first is being handled).
  const std::string out = file("long.exr");
  CommandResult r = interrupted(kScene + " --set camera.width=128 --set camera.height=128 " +
                                    "--set integrator.nSamples=65536 --time 600 -o " + out,
                                2);
  EXPECT_NE(r.out.find("rc=130"), std::string::npos) << r.out;
  EXPECT_TRUE(r.out.find("not written") != std::string::npos ||
              r.out.find("nothing written") != std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(out));
  r = interrupted(kScene + " --set camera.width=128 --set camera.height=128 " +
                      "--set integrator.nSamples=65536 --time 600 -o " + out,
                  1);
  EXPECT_NE(r.out.find("rc=130"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("nothing written"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace penumbra
