#include "core/image/atomic_file.h"
#include "core/math/temp_dir_test_support.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/image/image_io.h"
#include "core/math/error.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

class AtomicFileTest : public test::TempDirTest {
 protected:
  AtomicFileTest() : TempDirTest("penumbra-atomic-") {}
};

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

Image smallImage(float v, int w = 3, int h = 2) {
  Image img(w, h);
  for (float& f : img.rgb) f = v;
  return img;
}

TEST_F(AtomicFileTest, TempNameIsNextToTargetAndUnique) {
  const std::string a = atomicTempPath(file("x.exr")), b = atomicTempPath(file("x.exr"));
  EXPECT_NE(a, b);
  EXPECT_EQ(a.rfind(file("x.exr") + ".tmp-" + std::to_string(::getpid()) + "-", 0), 0u);
}

TEST_F(AtomicFileTest, NonexistentDirectoryThrowsAndCreatesNothing) {
  for (const char* name : {"a.exr", "a.pfm", "a.png"}) {
    const std::string path = (dir / "missing" / name).string();
    try {
      writeImage(path, smallImage(1.f));
      FAIL() << "expected Error for " << path;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
  EXPECT_FALSE(fs::exists(dir / "missing"));
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST_F(AtomicFileTest, PathInsideARegularFileThrows) {
  { std::ofstream(file("plain")) << "not a directory"; }
  EXPECT_THROW(writeImage(file("plain") + "/a.pfm", smallImage(1.f)), Error);
  EXPECT_THROW(writeImage(file("plain") + "/a.exr", smallImage(1.f)), Error);
  EXPECT_EQ(readFile(file("plain")), "not a directory");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST_F(AtomicFileTest, OverwriteReplacesCompletely) {
  for (const char* name : {"o.exr", "o.pfm", "o.png"}) {
    // A big old file, then a much smaller new one: nothing of the old may remain.
    writeImage(file(name), smallImage(0.25f, 64, 64));
    const auto bigSize = fs::file_size(file(name));
    writeImage(file(name), smallImage(0.75f, 2, 1));
    EXPECT_LT(fs::file_size(file(name)), bigSize);
    Image back = readImage(file(name));
    EXPECT_EQ(back.width, 2);
    EXPECT_EQ(back.height, 1);
  }
  writeImage(file("o.pfm"), smallImage(0.5f));
  EXPECT_EQ(readImage(file("o.pfm")).at(0, 0), Color3(0.5f));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 3);  // no temp files left
}

TEST_F(AtomicFileTest, FailedWriteLeavesOldFileIntact) {
  writeImage(file("keep.exr"), smallImage(0.5f));
  const std::string before = readFile(file("keep.exr"));
  // The writer fails after producing part of the temp file.
  EXPECT_THROW(writeFileAtomically(file("keep.exr"),
                                   [](const std::string& temp) {
                                     std::ofstream(temp) << "partial";
                                     throw Error("simulated failure");
                                   }),
               Error);
  // Empty image and bad metadata fail inside the format writers.
  EXPECT_THROW(writeImage(file("keep.exr"), Image{}), Error);
  ImageMetadata clash;
  clash.add("channels", "x");
  EXPECT_THROW(writeImage(file("keep.exr"), smallImage(1.f), clash), Error);
  EXPECT_EQ(readFile(file("keep.exr")), before);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST_F(AtomicFileTest, RenameFailureRemovesTemp) {
  // Target is an existing non-empty directory: rename() must fail, the temp must go away.
  fs::create_directories(dir / "target.pfm" / "child");
  EXPECT_THROW(writeImage(file("target.pfm"), smallImage(1.f)), Error);
  EXPECT_TRUE(fs::is_directory(dir / "target.pfm" / "child"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST_F(AtomicFileTest, ReadOnlyDirectoryLeavesOldFileIntact) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions";
  writeImage(file("ro.pfm"), smallImage(0.5f));
  const std::string before = readFile(file("ro.pfm"));
  fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
  EXPECT_THROW(writeImage(file("ro.pfm"), smallImage(2.f)), Error);
  fs::permissions(dir, fs::perms::owner_all);
  EXPECT_EQ(readFile(file("ro.pfm")), before);
}

TEST_F(AtomicFileTest, ReadOnlyExistingFileIsRefusedAndKept) {
  writeImage(file("ro.pfm"), smallImage(0.5f));
  const std::string before = readFile(file("ro.pfm"));
  fs::permissions(file("ro.pfm"), fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  try {
    writeImage(file("ro.pfm"), smallImage(2.f));
    FAIL() << "a read-only output was replaced";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("read-only"), std::string::npos) << e.what();
  }
  EXPECT_EQ(readFile(file("ro.pfm")), before);
  struct stat st;
  ASSERT_EQ(::stat(file("ro.pfm").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0444u);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST_F(AtomicFileTest, OutputsThatCannotBeWrittenAreRefusedBeforeAnyWork) {
  fs::create_directories(dir / "sub.exr");
  EXPECT_THROW(checkOutputPath(file("sub.exr")), Error);
  EXPECT_THROW(checkOutputPath(file("missing/a.exr")), Error);
  EXPECT_THROW(checkOutputPath("/proc/penumbra-test.exr"), Error);
  EXPECT_THROW(checkOutputPath("/dev/null"), Error);  // exists, not a regular file
  EXPECT_NO_THROW(checkOutputPath(file("fine.exr")));
  EXPECT_FALSE(fs::exists(file("fine.exr")));  // the probe leaves nothing behind
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

// A process id that is not running: a child that has exited and been reaped.
long deadPid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  return static_cast<long>(child);
}

TEST_F(AtomicFileTest, StaleTemporariesOfDeadProcessesAreRemovedOnTheNextWrite) {
  const std::string target = file("out.pfm");
  const std::string dead = target + ".tmp-" + std::to_string(deadPid()) + "-3";
  const std::string live = target + ".tmp-" + std::to_string(static_cast<long>(::getppid())) + "-0";
  const std::string other = file("other.pfm") + ".tmp-" + std::to_string(deadPid()) + "-0";
  const std::string odd = target + ".tmp-notapid";
  for (const std::string& p : {dead, live, other, odd}) std::ofstream(p) << "partial";
  writeImage(target, smallImage(1.f));
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_TRUE(fs::exists(live));   // its writer may still be running
  EXPECT_TRUE(fs::exists(other));  // another output's
  EXPECT_TRUE(fs::exists(odd));    // not a name this writer makes
  EXPECT_TRUE(fs::exists(target));
}

}  // namespace
}  // namespace penumbra
