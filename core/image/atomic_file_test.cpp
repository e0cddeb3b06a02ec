#include "core/image/atomic_file.h"
#include "core/image/temp_dir_fixture.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace penumbra
