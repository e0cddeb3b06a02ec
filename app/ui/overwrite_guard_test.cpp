#include "app/ui/overwrite_guard.h"

#include <gtest/gtest.h>

#include <fstream>

#include "core/math/temp_dir_test_support.h"

using namespace penumbra;
using namespace penumbra::ui;

namespace {
class OverwriteGuardTest : public test::TempDirTest {
 protected:
  OverwriteGuardTest() : TempDirTest("penumbra-overwrite-guard-") {}
};
}  // namespace

TEST_F(OverwriteGuardTest, ANewPathIsWrittenAtOnce) {
  OverwriteGuard guard;
  EXPECT_TRUE(guard.allows(file("new.xml")));
  EXPECT_TRUE(guard.allows(file("new.xml")));
}

TEST_F(OverwriteGuardTest, AnExistingFileTakesASecondRequestForTheSamePath) {
  const std::string a = file("a.xml"), b = file("b.xml");
  std::ofstream(a) << "x";
  std::ofstream(b) << "y";
  OverwriteGuard guard;
  EXPECT_FALSE(guard.allows(a));
  EXPECT_TRUE(guard.allows(a));
  EXPECT_FALSE(guard.allows(a)) << "each replacement needs its own confirmation";
  EXPECT_FALSE(guard.allows(b)) << "a request for another path disarms the first";
  EXPECT_FALSE(guard.allows(a));
  EXPECT_TRUE(guard.allows(a));
  EXPECT_EQ(OverwriteGuard::refusal(a, "Save as"), a + " exists: press Save as again to replace it");
}
