// `penumbra render --display-server` against tev servers that misbehave (app/net/fake_tev_test_support.h, 127.0.0.1
// only): one that never reads, closes at once, resets the connection, sends garbage, reads slowly,
// never accepts, or has a full backlog, beside a well-behaved one. For each, what the stream promises
// (docs/reliability.md, "tev stream"):
//   * the command takes at most TevStreamOptions::waitSeconds longer than without the stream, beyond
//     the rendering itself (which the machine's load moves by seconds on a busy CI machine);
//   * it writes the same bytes as without the stream;
//   * Ctrl-C writes the completed passes as without the stream (the last pass boundary published,
//     at most about half a second and two passes old): an image equal to an uninterrupted render of
//     that many passes, and the process exits within the same bound.
// The frames (7 MB) are larger than what the loopback socket buffers hold, so a server that does not
// read holds up the sending thread. Times are checked with a margin of 3 s beyond the bound (a loaded
// CI machine); every wait is bounded.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "app/net/fake_tev_test_support.h"
#include "app/net/tev_streamer.h"
#include "core/image/image_io.h"
#include "core/math/temp_dir_test_support.h"
#include "tests/child_process.h"
#include "tests/run_command.h"

namespace penumbra {
namespace {

using test::FakeTev;
using Mode = FakeTev::Mode;

const std::string kScene = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/hw2/Tests/sphere-area.xml";
// Passes of ~0.1 s: a render of kSpp takes a second or two.
const std::vector<std::string> kSettings = {
    "--set", "camera.width=640", "--set", "camera.height=480", "--threads", "2"};
constexpr int kSpp = 16;
// Ctrl-C comes once the child has used this much CPU time, however long a loaded machine makes that
// take: dozens of passes (a pass costs ~30 ms of CPU here, 100 ms on a machine three times slower).
// The pass boundary written is at most about 0.5 s and two passes old, i.e. at most ~1.1 s of CPU time
// of the two render threads, so it holds at least kMinKeptPasses; an old boundary, such as that of
// the first passes, does not.
constexpr double kInterruptAfterCpuSeconds = 2;
constexpr int kMinKeptPasses = 5;
// What the stream may add after the render (TevStreamOptions::waitSeconds), and the test's margin.
const double kBoundSeconds = net::TevStreamOptions{}.waitSeconds;
constexpr double kMarginSeconds = 3;

enum class Warns { None, One, AtMostOne };  // a slow reader may or may not be too slow for the bound

struct Hostile {
  Mode mode;
  const char* name;
  Warns warns;
};

std::string fileBytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

int countOf(const std::string& text, const std::string& word) {
  int n = 0;
  for (size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++n;
  return n;
}

std::string quoted(const std::vector<std::string>& args) {
  std::string s;
  for (const std::string& a : args) s += " '" + a + "'";
  return s;
}

struct Timed {
  test::CommandResult result;
  double seconds = 0;
  // The command's time beyond rendering (starting, loading, writing, and the stream's end): the wall
  // time less the rendering seconds of its summary line.
  double beyondRendering() const {
    const size_t at = result.out.find(" spp, ");
    return at == std::string::npos ? seconds : seconds - std::stod(result.out.substr(at + 6));
  }
};

// `penumbra render` of the scene with `extra` arguments, timed.
Timed render(const std::vector<std::string>& extra) {
  std::vector<std::string> args = {"render", kScene};
  args.insert(args.end(), kSettings.begin(), kSettings.end());
  args.insert(args.end(), extra.begin(), extra.end());
  const auto t0 = std::chrono::steady_clock::now();
  Timed t;
  t.result = test::runCommand("timeout 300 '" PENUMBRA_BINARY "'" + quoted(args));
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return t;
}

class HostileTev : public test::TempDirTest, public ::testing::WithParamInterface<Hostile> {
 protected:
  HostileTev() : TempDirTest("penumbra-hostile-tev-") {}
  void TearDown() override {
    TempDirTest::TearDown();
    // The name is "TEST/PARAM": the directory is PREFIX-TEST/PARAM; remove PREFIX-TEST once empty.
    std::error_code ec;
    if (dir.parent_path() != std::filesystem::temp_directory_path())
      std::filesystem::remove(dir.parent_path(), ec);
  }
};

// The whole render with the stream: no longer than without it plus the bound, the same bytes.
TEST_P(HostileTev, RenderKeepsItsTimeAndItsBytes) {
  const Hostile h = GetParam();
  FakeTev tev(h.mode);
  const std::string plain = file("plain.pfm"), streamed = file("streamed.pfm");
  const Timed without = render({"--spp", std::to_string(kSpp), "-o", plain});
  ASSERT_EQ(without.result.exitCode, 0) << without.result.out;
  const Timed with =
      render({"--spp", std::to_string(kSpp), "--display-server", tev.address(), "-o", streamed});
  ASSERT_EQ(with.result.exitCode, 0) << with.result.out;
  std::printf(
      "[ measured ] %-12s render %.2f s without the stream, %.2f s with it (beyond rendering: %.2f s, "
      "%.2f s)\n",
      h.name, without.seconds, with.seconds, without.beyondRendering(), with.beyondRendering());
  EXPECT_LE(with.beyondRendering(), without.beyondRendering() + kBoundSeconds + kMarginSeconds)
      << with.result.out;
  EXPECT_EQ(fileBytes(streamed), fileBytes(plain));
  // At most one warning, and that one about the display server.
  const int warnings = countOf(with.result.out, "warning");
  EXPECT_EQ(countOf(with.result.out, "warning: display server " + tev.address() + ": "), warnings)
      << with.result.out;
  if (h.warns == Warns::AtMostOne)
    EXPECT_LE(warnings, 1) << with.result.out;
  else
    EXPECT_EQ(warnings, h.warns == Warns::One ? 1 : 0) << with.result.out;
}

// Ctrl-C during a streamed render: the completed passes are written, as without the stream, and the
// process ends within the bound.
TEST_P(HostileTev, InterruptKeepsTheCompletedPasses) {
  const Hostile h = GetParam();
  FakeTev tev(h.mode);
  const std::string interrupted = file("interrupted.exr");
  std::vector<std::string> args = {PENUMBRA_BINARY, "render", kScene};
  args.insert(args.end(), kSettings.begin(), kSettings.end());
  args.insert(args.end(), {"--time", "120", "--display-server", tev.address(), "-o", interrupted});
  test::ChildProcess child;
  ASSERT_TRUE(child.start(args, file("child.log")));
  const auto started = std::chrono::steady_clock::now();
  while (child.cpuSeconds() < kInterruptAfterCpuSeconds &&
         std::chrono::steady_clock::now() - started < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const double cpuAtSignal = child.cpuSeconds();
  child.signal(SIGINT);
  const auto t0 = std::chrono::steady_clock::now();
  const int code = child.wait(60);
  const double exitSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::string out = child.output();
  ASSERT_EQ(code, 130) << out;
  ASSERT_TRUE(std::filesystem::exists(interrupted)) << out;
  ImageMetadata meta;
  const Image got = readExr(interrupted, &meta);
  for (const char* key : {"spp", "seconds", "interrupted"}) ASSERT_NE(meta.find(key), nullptr) << key;
  EXPECT_EQ(*meta.find("interrupted"), "true");
  const int spp = std::stoi(*meta.find("spp"));
  const double kept = std::stod(*meta.find("seconds"));
  std::printf(
      "[ measured ] %-12s Ctrl-C after %.1f CPU s: %d spp (%.2f s of rendering) written, exit %.2f s after "
      "the signal\n",
      h.name, cpuAtSignal, spp, kept, exitSeconds);
  ASSERT_GT(spp, 0) << out;
  EXPECT_GE(spp, kMinKeptPasses) << "an old pass boundary was written\n" << out;
  EXPECT_LE(exitSeconds, kBoundSeconds + kMarginSeconds) << out;
  // A valid prefix: exactly what an uninterrupted render of that many passes writes.
  const std::string whole = file("whole.exr");
  const Timed reference = render({"--spp", std::to_string(spp), "-o", whole});
  ASSERT_EQ(reference.result.exitCode, 0) << reference.result.out;
  const Image want = readExr(whole);
  ASSERT_EQ(got.rgb.size(), want.rgb.size());
  EXPECT_EQ(std::memcmp(got.rgb.data(), want.rgb.data(), got.rgb.size() * sizeof(float)), 0);
}

INSTANTIATE_TEST_SUITE_P(Servers, HostileTev,
                         ::testing::Values(Hostile{Mode::Serve, "Serve", Warns::None},
                                           Hostile{Mode::NeverRead, "NeverRead", Warns::One},
                                           Hostile{Mode::CloseAtOnce, "CloseAtOnce", Warns::One},
                                           Hostile{Mode::Reset, "Reset", Warns::One},
                                           Hostile{Mode::Garbage, "Garbage", Warns::None},
                                           Hostile{Mode::SlowReader, "SlowReader", Warns::AtMostOne},
                                           Hostile{Mode::NeverAccept, "NeverAccept", Warns::One},
                                           Hostile{Mode::BacklogFull, "BacklogFull", Warns::One}),
                         [](const ::testing::TestParamInfo<Hostile>& info) { return info.param.name; });

}  // namespace
}  // namespace penumbra
