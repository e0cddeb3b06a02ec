#include "app/net/tev_streamer.h"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "app/net/fake_tev_test_support.h"

namespace penumbra::net {
namespace {

using test::FakeTev;
using test::serverAt;
using test::unusedPort;

// The streamer's own paths, in process: frames sent with send() arrive whole; a refused connection is
// one warning and send() returns at once afterwards.
TEST(TevStreamer, SentFramesArriveWholeWithTheirLayers) {
  FakeTev tev;
  std::vector<std::string> warnings;
  {
    TevStreamOptions o;
    o.warn = [&](const std::string& w) { warnings.push_back(w); };
    TevStreamer s(serverAt(tev.port()), o);
    Image mean(130, 3), err(130, 3);
    for (size_t i = 0; i < mean.rgb.size(); ++i) mean.rgb[i] = float(i), err.rgb[i] = 0.5f * float(i);
    s.send({"a", mean, err});
    s.send({"a", mean, err});
    s.finish(TevFrame{"b", mean, Image()});
    EXPECT_EQ(s.updatesSent(), 3u);
    EXPECT_FALSE(s.failed());
  }
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  ASSERT_TRUE(tev.waitForStreamsEnded(1, 5));
  const auto images = tev.images();
  ASSERT_EQ(images.size(), 2u);
  EXPECT_EQ(images.at("a").channels.size(), 6u);
  EXPECT_EQ(images.at("a").creates, 1);  // the same name, size and channels: created once
  EXPECT_EQ(images.at("b").channels.size(), 3u);
  int updates = 0;
  EXPECT_EQ(images.at("a").coverage("stderr.B", &updates), "");
  EXPECT_EQ(updates, 2);
  EXPECT_EQ(images.at("a").at("stderr.B", 129, 2), 0.5f * float((2 * 130 + 129) * 3 + 2));
}

TEST(TevStreamer, RefusedConnectionIsOneWarning) {
  int fd = -1;
  const int port = unusedPort(fd);
  ASSERT_GT(port, 0);
  std::vector<std::string> warnings;
  {
    TevStreamOptions o;
    o.warn = [&](const std::string& w) { warnings.push_back(w); };
    TevStreamer s(serverAt(port), o);
    s.send({"a", Image(4, 4), Image()});
    s.send({"a", Image(4, 4), Image()});
    EXPECT_TRUE(s.failed());
  }
  ::close(fd);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(
      warnings[0].find("warning: display server 127.0.0.1:" + std::to_string(port) + ": cannot connect"),
      std::string::npos)
      << warnings[0];
}

// An exception on the sending thread ends the stream like a socket fault: one warning naming it, the
// waiting caller released, later frames dropped. Here the encoder throws on a frame whose standard
// error is smaller than its mean (its first tile lies outside the error layer).
TEST(TevStreamer, AnExceptionWhileSendingEndsTheStreamWithOneWarning) {
  FakeTev tev;
  std::vector<std::string> warnings;
  {
    TevStreamOptions o;
    o.warn = [&](const std::string& w) { warnings.push_back(w); };
    TevStreamer s(serverAt(tev.port()), o);
    s.send({"a", Image(4, 4), Image()});
    EXPECT_FALSE(s.failed());
    s.send({"a", Image(200, 3), Image(100, 3)});
    EXPECT_TRUE(s.failed());
    s.send({"a", Image(4, 4), Image()});
    s.finish(TevFrame{"a", Image(4, 4), Image()});
    EXPECT_EQ(s.updatesSent(), 1u);
  }
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("warning: display server 127.0.0.1:" + std::to_string(tev.port()) +
                             ": cannot send (tev update: tile outside the 100x3 image of layer 'stderr.'); "
                             "continuing without it"),
            std::string::npos)
      << warnings[0];
}

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// A snapshot of w x h pixels, as a render loop offers it.
FilmSnapshot snapshotOf(int w, int h, uint64_t version) {
  FilmSnapshot s;
  s.version = version;
  s.spp = 1;
  s.mean = Image(w, h);
  s.standardError = Image(w, h);
  return s;
}

// Waits (at most 10 s) until the stream wants a frame: connected and idle.
bool waitUntilWanted(const TevStreamer& s) {
  const auto t0 = Clock::now();
  while (!s.wanted().frame && !s.failed() && secondsSince(t0) < 10)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  return s.wanted().frame;
}

// Whoever waits for the stream (finish, send) waits at most waitSeconds, whatever tev does: here a tev
// that never reads, while a 12 MB frame is being sent. Margins: a loaded machine.
TEST(TevStreamer, FinishAndSendAreBoundedWhenTevStopsReading) {
  for (const bool viaSend : {false, true}) {
    FakeTev tev(FakeTev::Mode::NeverRead);
    std::vector<std::string> warnings;
    TevStreamOptions o;
    o.waitSeconds = 0.5;
    o.warn = [&](const std::string& w) { warnings.push_back(w); };
    TevStreamer s(serverAt(tev.port()), o);
    ASSERT_TRUE(waitUntilWanted(s));
    s.offer("big", snapshotOf(1024, 1024, 1), true);  // fills the socket buffers, then waits for tev
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    const auto t0 = Clock::now();
    if (viaSend)
      s.send(TevFrame{"last", Image(1024, 1024), Image(), false});
    else
      s.finish(TevFrame{"last", Image(1024, 1024), Image(), false});
    EXPECT_LT(secondsSince(t0), o.waitSeconds + 2.0) << (viaSend ? "send" : "finish");
    EXPECT_TRUE(s.failed());
    s.finish();
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("too slow: still busy 0.5 s after "), std::string::npos) << warnings[0];
  }
}

// A tev whose backlog is full: connecting hangs (SYNs are dropped) for up to connectSeconds, but
// finish() gives up after waitSeconds.
TEST(TevStreamer, FinishIsBoundedWhileConnecting) {
  FakeTev tev(FakeTev::Mode::BacklogFull);
  std::vector<std::string> warnings;
  TevStreamOptions o;
  o.connectSeconds = 30;
  o.waitSeconds = 0.5;
  o.warn = [&](const std::string& w) { warnings.push_back(w); };
  TevStreamer s(serverAt(tev.port()), o);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const auto t0 = Clock::now();
  s.finish(TevFrame{"last", Image(8, 8), Image(), false});
  EXPECT_LT(secondsSince(t0), o.waitSeconds + 2.0);
  EXPECT_EQ(tev.connections(), 0);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("too slow"), std::string::npos) << warnings[0];
}

// offer() never waits: while a frame is being sent, further offers are dropped at once.
TEST(TevStreamer, OffersWhileSendingAreDroppedAtOnce) {
  FakeTev tev(FakeTev::Mode::NeverRead);
  TevStreamOptions o;
  o.minIntervalSeconds = 0;
  o.waitSeconds = 0.2;
  o.warn = [](const std::string&) {};
  TevStreamer s(serverAt(tev.port()), o);
  ASSERT_TRUE(waitUntilWanted(s));
  s.offer("big", snapshotOf(1024, 1024, 1), true);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_FALSE(s.wanted().frame);
  const auto t0 = Clock::now();
  for (uint64_t v = 2; v < 50; ++v) s.offer("big", snapshotOf(64, 64, v), true);
  EXPECT_LT(secondsSince(t0), 1.0);
  EXPECT_EQ(s.updatesSent(), 0u);
}

// A tev that sends bytes of its own (tev sends none) is read past: the stream goes on, images arrive.
TEST(TevStreamer, BytesFromTheServerAreIgnored) {
  FakeTev tev(FakeTev::Mode::Garbage);
  std::vector<std::string> warnings;
  {
    TevStreamOptions o;
    o.warn = [&](const std::string& w) { warnings.push_back(w); };
    TevStreamer s(serverAt(tev.port()), o);
    Image mean(300, 200);
    for (int i = 0; i < 5; ++i) {
      s.send({"a", mean, Image()});
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    s.finish();
    EXPECT_EQ(s.updatesSent(), 5u);
  }
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  ASSERT_TRUE(tev.waitForStreamsEnded(1, 5));
  EXPECT_TRUE(tev.problems().empty()) << tev.problems().front();
  int updates = 0;
  EXPECT_EQ(tev.images().at("a").coverage("R", &updates), "");
  EXPECT_EQ(updates, 5);
}

// The viewer offers a frame after every poll and, when it closes, sends the last one: an offered frame
// not yet begun is replaced by it, and send() returns once that is sent. A send() that never returned
// would hang the test: a watchdog ends the process with a message instead.
TEST(TevStreamer, SendRightAfterAnOfferReturns) {
  FakeTev tev;
  TevStreamOptions o;
  o.minIntervalSeconds = 0;
  TevStreamer s(serverAt(tev.port()), o);
  ASSERT_TRUE(waitUntilWanted(s));
  std::atomic<bool> done{false};
  std::thread watchdog([&] {
    const auto t0 = Clock::now();
    while (!done && secondsSince(t0) < 60) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (!done) {
      std::fprintf(stderr, "TevStreamer.SendRightAfterAnOfferReturns: send() did not return in 60 s\n");
      std::_Exit(1);
    }
  });
  for (uint64_t v = 1; v <= 200; ++v) {
    s.offer("a", snapshotOf(16, 16, v));
    s.send(TevFrame{"a", Image(16, 16), Image(), false});
  }
  done = true;
  watchdog.join();
  s.finish();
  EXPECT_FALSE(s.failed());
  EXPECT_GE(s.updatesSent(), 200u);
}

}  // namespace
}  // namespace penumbra::net
