#include "core/math/bounded_read.h"
#include "core/math/temp_dir_test_support.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "core/math/error.h"

namespace penumbra {
namespace {

class BoundedReadTest : public test::TempDirTest {
 protected:
  BoundedReadTest() : TempDirTest("penumbra-bounded-read-") {}
};

std::string messageOf(const std::string& path, uint64_t maxBytes) {
  try {
    readRegularFile(path, maxBytes, "mesh file");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST_F(BoundedReadTest, ReadsARegularFileWhole) {
  std::ofstream(file("a.obj"), std::ios::binary) << "v 0 0 0\r\nf 1 2 3";
  EXPECT_EQ(readRegularFile(file("a.obj"), 100, "mesh file"), "v 0 0 0\r\nf 1 2 3");
}

TEST_F(BoundedReadTest, RefusesDirectoriesDevicesMissingAndOversizedFiles) {
  EXPECT_NE(messageOf(dir.string(), 1 << 20).find("is a directory"), std::string::npos);
  EXPECT_NE(messageOf("/dev/zero", 1 << 20).find("not a regular file"), std::string::npos);
  EXPECT_NE(messageOf(file("missing.obj"), 1 << 20).find("No such file"), std::string::npos);
  std::ofstream(file("big.obj")) << std::string(2000, 'x');
  EXPECT_NE(messageOf(file("big.obj"), 1000).find("larger than the limit"), std::string::npos);
}

}  // namespace
}  // namespace penumbra
