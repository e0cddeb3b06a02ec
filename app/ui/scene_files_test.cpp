// SceneFiles: loads on the calling thread and on a loader thread, the watched file's changes, the
// recent list and the sibling scenes.
#include "app/ui/scene_files.h"

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "core/math/error.h"
#include "core/math/temp_dir_test_support.h"

using namespace penumbra;
using namespace penumbra::ui;

namespace fs = std::filesystem;

namespace {

class SceneFilesTest : public test::TempDirTest {
 protected:
  SceneFilesTest() : TempDirTest("penumbra-scene-files-") {}
  std::string scene(const std::string& name) {
    std::ofstream(dir / name) << defaultSceneXml();
    return file(name);
  }
};

}  // namespace

TEST_F(SceneFilesTest, LoadsHereAndOnALoaderThreadWithTheOverrides) {
  SceneFiles files(SceneFiles::Overrides{{"camera.width", "40"}});
  double seconds = -1;
  EXPECT_EQ(files.load(scene("a.xml"), seconds).settings.camera.width, 40);
  EXPECT_GE(seconds, 0.0);
  EXPECT_GE(files.blockingSeconds(), seconds);
  EXPECT_THROW(files.load(file("missing.xml"), seconds), Error);

  files.loadAsync(scene("b.xml"));
  EXPECT_TRUE(files.loading());
  EXPECT_EQ(files.loadingPath(), file("b.xml"));
  auto t0 = std::chrono::steady_clock::now();
  while (!files.loadFinished() && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(30))
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ASSERT_TRUE(files.loadFinished());
  EXPECT_EQ(files.takeLoaded().settings.camera.width, 40);
  EXPECT_FALSE(files.loading());

  files.loadAsync(file("missing.xml"));  // the error comes with the result
  files.loadAsync(scene("c.xml"));       // waits for the one in flight: the newest wins
  EXPECT_EQ(files.loadingPath(), file("c.xml"));
  EXPECT_NO_THROW(files.takeLoaded());
}

TEST_F(SceneFilesTest, TheWatchedFilesChangesAndTheLists) {
  SceneFiles files(SceneFiles::Overrides{});
  EXPECT_FALSE(files.changed());  // nothing watched
  const std::string a = scene("a.xml");
  files.watch(a);
  EXPECT_FALSE(files.changed());
  fs::last_write_time(a, fs::last_write_time(a) + std::chrono::seconds(5));
  std::this_thread::sleep_for(std::chrono::milliseconds(510));  // looks at most twice a second
  EXPECT_TRUE(files.changed());

  for (int i = 0; i < 12; ++i) files.rememberRecent(file("s" + std::to_string(i) + ".xml"));
  files.rememberRecent(file("s5.xml"));
  ASSERT_EQ(files.recent().size(), 10u);
  EXPECT_EQ(files.recent().front(), file("s5.xml"));
  EXPECT_EQ(files.recent()[1], file("s11.xml"));

  scene("b.xml");
  std::ofstream(dir / "notes.txt") << "x";
  EXPECT_EQ(siblingScenes(a), (std::vector<std::string>{file("a.xml"), file("b.xml")}));
}
