// End-to-end tests of --display-server (streaming to tev) in render, converge and view, against a
// fake tev in this process (app/net/fake_tev_test_support.h, 127.0.0.1 only): what arrives is decoded and rebuilt and
// must equal the files the commands write; a viewer that closes early, never accepts or refuses costs
// one warning and nothing else. Every command runs under `timeout`, every wait is bounded.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "app/net/fake_tev_test_support.h"
#include "core/image/image_io.h"
#include "core/math/temp_dir_test_support.h"
#include "tests/run_command.h"

namespace penumbra {
namespace {

using test::FakeTev;

const std::string kScene = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/hw2/Tests/sphere-area.xml";
// 200 x 150: a row and a column of partial 128-pixel tiles.
const std::string kSmall = " --set camera.width=200 --set camera.height=150 --threads 2";

test::CommandResult penumbra(const std::string& args, const char* binary = PENUMBRA_BINARY) {
  return test::runCommand(std::string("timeout 120 '") + binary + "' " + args);
}

std::string fileBytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

int countOf(const std::string& text, const std::string& word) {
  int n = 0;
  for (size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++n;
  return n;
}

// The channels of `received` named prefix R, G, B equal `image` bit for bit.
void expectChannelsEqual(const FakeTev::ReceivedImage& received, const std::string& prefix,
                         const Image& image) {
  ASSERT_EQ(received.width, image.width);
  ASSERT_EQ(received.height, image.height);
  int mismatches = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const float got = received.at(prefix + "RGB"[c], x, y),
                    want = image.rgb[image.index(x, y) + size_t(c)];
        if (std::memcmp(&got, &want, sizeof got) != 0 && mismatches++ < 5)
          ADD_FAILURE() << prefix << "RGB"[c] << " at " << x << "," << y << ": " << got << " != " << want;
      }
  EXPECT_EQ(mismatches, 0);
}

class DisplayServer : public test::TempDirTest {
 protected:
  DisplayServer() : TempDirTest("penumbra-tev-") {}
};

TEST_F(DisplayServer, RenderStreamsTheImageItWrites) {
  FakeTev tev;
  const std::string out = file("out.pfm");
  test::CommandResult r = penumbra("render '" + kScene + "'" + kSmall + " --time 1 --display-server " +
                                   tev.address() + " -o " + out);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
  ASSERT_TRUE(tev.waitForStreamsEnded(1, 10));
  EXPECT_TRUE(tev.problems().empty()) << tev.problems().front();
  const auto images = tev.images();
  ASSERT_EQ(images.size(), 1u);
  ASSERT_EQ(images.begin()->first, "sphere-area [area]");
  const FakeTev::ReceivedImage& img = images.begin()->second;
  EXPECT_EQ(img.creates, 1);
  EXPECT_EQ(img.channels, (std::vector<std::string>{"R", "G", "B", "stderr.R", "stderr.G", "stderr.B"}));
  // Whole updates only: the colour while rendering and at the end, the error at least at the end.
  int colourUpdates = 0, errorUpdates = 0;
  EXPECT_EQ(img.coverage("R", &colourUpdates), "");
  EXPECT_EQ(img.coverage("stderr.R", &errorUpdates), "");
  EXPECT_GE(colourUpdates, 2) << "no update while rendering";
  EXPECT_GE(errorUpdates, 1);
  expectChannelsEqual(img, "", readImage(out));
  // The standard error of a 1-second render: finite, non-negative, not zero everywhere.
  double sum = 0;
  for (const std::string c : {"stderr.R", "stderr.G", "stderr.B"})
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const float e = img.at(c, x, y);
        ASSERT_TRUE(std::isfinite(e) && e >= 0) << c << " " << x << "," << y << ": " << e;
        sum += e;
      }
  EXPECT_GT(sum, 0);
}

TEST_F(DisplayServer, ReferenceRenderStreamsItsStandardError) {
  FakeTev tev;
  const std::string out = file("ref.exr");
  test::CommandResult r = penumbra("render --reference '" + kScene + "'" + kSmall +
                                   " --spp 16 --display-server " + tev.address() + " -o " + out);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  ASSERT_TRUE(tev.waitForStreamsEnded(1, 10));
  const auto images = tev.images();
  ASSERT_EQ(images.count("sphere-area [solid-angle]"), 1u);
  const FakeTev::ReceivedImage& img = images.at("sphere-area [solid-angle]");
  expectChannelsEqual(img, "", readImage(out));
  expectChannelsEqual(img, "stderr.", readImage(file("ref.stderr.exr")));
}

// A render that streams writes exactly the file it writes without streaming.
void expectSameImageAsWithoutStreaming(const std::string& dir, const std::string& streamed) {
  const std::string plain = dir + "/plain.pfm";
  test::CommandResult r = penumbra("render '" + kScene + "'" + kSmall + " --spp 8 -o " + plain);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_EQ(fileBytes(streamed), fileBytes(plain));
}

// The small render at 8 spp, streamed to `address`, written to `out`.
test::CommandResult renderStreamingTo(const std::string& address, const std::string& out) {
  return penumbra("render '" + kScene + "'" + kSmall + " --spp 8 --display-server " + address + " -o " + out);
}

// One "warning: display server 127.0.0.1:PORT: ..." line and no other warning.
void expectOneWarning(const std::string& out, int port) {
  EXPECT_EQ(countOf(out, "warning"), 1) << out;
  EXPECT_EQ(countOf(out, "warning: display server 127.0.0.1:" + std::to_string(port) + ": "), 1) << out;
}

TEST_F(DisplayServer, ViewerClosingAfterTheFirstPacketIsOneWarning) {
  FakeTev tev(FakeTev::Mode::CloseAfterFirstPacket);
  const std::string out = file("out.pfm");
  test::CommandResult r = renderStreamingTo(tev.address(), out);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  expectOneWarning(r.out, tev.port());
  EXPECT_NE(r.out.find("closed the connection"), std::string::npos) << r.out;
  EXPECT_EQ(tev.packets(), 1);
  expectSameImageAsWithoutStreaming(dir.string(), out);
}

TEST_F(DisplayServer, ViewerNeverAcceptingIsOneWarning) {
  FakeTev tev(FakeTev::Mode::NeverAccept);
  const std::string out = file("out.pfm");
  test::CommandResult r = renderStreamingTo(tev.address(), out);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  expectOneWarning(r.out, tev.port());
  EXPECT_EQ(tev.connections(), 0);
  expectSameImageAsWithoutStreaming(dir.string(), out);
}

TEST_F(DisplayServer, RefusedConnectionIsOneWarning) {
  // A port bound (so nobody else takes it during the test) but not listening: connections are refused.
  int fd = -1;
  const int port = test::unusedPort(fd);
  ASSERT_GT(port, 0);
  const std::string out = file("out.pfm");
  test::CommandResult r = renderStreamingTo("127.0.0.1:" + std::to_string(port), out);
  ::close(fd);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  expectOneWarning(r.out, port);
  EXPECT_NE(r.out.find("refused"), std::string::npos) << r.out;
  expectSameImageAsWithoutStreaming(dir.string(), out);
}

TEST_F(DisplayServer, MalformedValuesAreArgumentErrorsBeforeRendering) {
  // None of these reaches a resolver: they are rejected by their form.
  for (const char* spec : {"127.0.0.1:0", "127.0.0.1:65536", "127.0.0.1:", "127.0.0.1:x", ":14158",
                           "no_such_host", "bad..host", "::1", "[::1", "[zz]:1"}) {
    const std::string out = file("out.pfm");
    test::CommandResult r =
        penumbra("render '" + kScene + "'" + kSmall + " --spp 1 --display-server '" + spec + "' -o " + out);
    EXPECT_EQ(r.exitCode, 2) << spec << "\n" << r.out;
    EXPECT_NE(r.out.find(std::string("--display-server ") + spec + ": "), std::string::npos) << r.out;
    EXPECT_FALSE(std::filesystem::exists(out)) << spec;
    EXPECT_EQ(r.out.find("spp,"), std::string::npos) << spec << ": rendered\n" << r.out;
  }
  // The same check in converge and view, before they load anything.
  test::CommandResult c =
      penumbra("converge /nonexistent.xml --spp 1 --display-server no_such_host -o " + file("c"));
  EXPECT_EQ(c.exitCode, 2) << c.out;
  EXPECT_NE(c.out.find("--display-server no_such_host: "), std::string::npos) << c.out;
  test::CommandResult v =
      penumbra("view /nonexistent.xml --frames 1 --display-server no_such_host", PENUMBRA_OFFSCREEN_BINARY);
  EXPECT_EQ(v.exitCode, 2) << v.out;
  EXPECT_NE(v.out.find("--display-server no_such_host: "), std::string::npos) << v.out;
}

TEST_F(DisplayServer, ConvergeStreamsEachStrategysFinalImage) {
  FakeTev tev;
  test::CommandResult r = penumbra(
      "converge '" + std::string(PENUMBRA_SOURCE_DIR) +
      "/scenes/analytic/plane-sphere-light.xml' --set camera.width=40 --set camera.height=32 --spp 4 "
      "--strategies area,solid-angle --display-server " +
      tev.address() + " -o " + file("converge"));
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
  ASSERT_TRUE(tev.waitForStreamsEnded(1, 10));
  EXPECT_TRUE(tev.problems().empty()) << tev.problems().front();
  const auto images = tev.images();
  ASSERT_EQ(images.size(), 2u);
  for (const char* name :
       {"plane-sphere-light [area] converge", "plane-sphere-light [solid-angle] converge"}) {
    ASSERT_EQ(images.count(name), 1u) << name;
    const FakeTev::ReceivedImage& img = images.at(name);
    EXPECT_EQ(img.channels, (std::vector<std::string>{"R", "G", "B"}));
    int updates = 0;
    EXPECT_EQ(img.coverage("R", &updates), "");
    EXPECT_EQ(updates, 1) << name;  // the final image, once
    for (float v : img.planes[0]) ASSERT_TRUE(std::isfinite(v) && v >= 0) << name;
  }
}

TEST_F(DisplayServer, ViewerStreamsItsImage) {
  FakeTev tev;
  test::CommandResult r =
      penumbra("view '" + kScene + "'" + kSmall +
                   " --set sampler.sampleCount=4 --frames 3 --window 720x560 --display-server " +
                   tev.address() + " --screenshot " + file("view.png"),
               PENUMBRA_OFFSCREEN_BINARY);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
  ASSERT_TRUE(tev.waitForStreamsEnded(1, 10));
  EXPECT_TRUE(tev.problems().empty()) << tev.problems().front();
  const auto images = tev.images();
  ASSERT_EQ(images.count("sphere-area [area]"), 1u);
  const FakeTev::ReceivedImage& img = images.at("sphere-area [area]");
  EXPECT_EQ(img.channels, (std::vector<std::string>{"R", "G", "B"}));
  EXPECT_EQ(img.coverage("R"), "");
  // The last image sent is the finished accumulation: what `render` writes at the same settings.
  const std::string out = file("render.pfm");
  ASSERT_EQ(penumbra("render '" + kScene + "'" + kSmall + " --set sampler.sampleCount=4 -o " + out).exitCode,
            0);
  expectChannelsEqual(img, "", readImage(out));
}

}  // namespace
}  // namespace penumbra
