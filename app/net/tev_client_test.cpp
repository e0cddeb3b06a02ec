#include "app/net/tev_client.h"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "app/net/fake_tev_test_support.h"
#include "app/net/tev_protocol.h"
#include "core/math/error.h"

namespace penumbra::net {
namespace {

using test::FakeTev;
using test::serverAt;
using test::unusedPort;

TEST(DisplayServerSpec, HostAloneTakesTevsPort) {
  DisplayServer s = resolveDisplayServer("127.0.0.1");
  EXPECT_EQ(s.host, "127.0.0.1");
  EXPECT_EQ(s.port, 14158);
  EXPECT_EQ(s.label(), "127.0.0.1:14158");
  ASSERT_FALSE(s.addresses.empty());
  EXPECT_EQ(s.addresses[0].family, AF_INET);
}

TEST(DisplayServerSpec, PortsAndIpv6Literals) {
  EXPECT_EQ(resolveDisplayServer("127.0.0.1:1").port, 1);
  EXPECT_EQ(resolveDisplayServer("127.0.0.1:65535").port, 65535);
  DisplayServer v6 = resolveDisplayServer("[::1]:7");
  EXPECT_EQ(v6.host, "::1");
  EXPECT_EQ(v6.port, 7);
  EXPECT_EQ(v6.label(), "[::1]:7");
  EXPECT_EQ(resolveDisplayServer("[::1]").port, 14158);
}

TEST(DisplayServerSpec, MalformedValuesNameWhatWasExpected) {
  // Rejected by their form, before any resolver is asked.
  for (const char* bad :
       {"", ":1", "h:", "h:0", "h:65536", "h:123456", "h:-1", "h:1x", "a:b:c", "::1", "[::1", "[::1]x",
        "[::1]:", "[1.2.3.4]", "under_score", "-lead", "trail-", "a..b", "sp ace"}) {
    try {
      resolveDisplayServer(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind(std::string("--display-server ") + bad + ": ", 0), 0u)
          << e.what();
    }
  }
}

// Connects `c` to the fake tev and writes one small CreateImage packet (kept in `packet`).
void connectAndSendOnePacket(const FakeTev& tev, TevConnection& c, std::vector<uint8_t>& packet,
                             std::string& why) {
  ASSERT_TRUE(c.connect(serverAt(tev.port()), 3, why)) << why;
  encodeCreateImage({false, "n", 4, 4, {"Y"}}, packet);
  ASSERT_TRUE(c.write(packet, 3, why)) << why;
}

TEST(TevConnection, WritesAndEndsAStreamThePeerReadToTheEnd) {
  FakeTev tev;
  TevConnection c;
  std::string why;
  std::vector<uint8_t> packet;
  ASSERT_NO_FATAL_FAILURE(connectAndSendOnePacket(tev, c, packet, why));
  EXPECT_FALSE(c.peerClosed());
  EXPECT_TRUE(c.finish(3, why)) << why;
  EXPECT_TRUE(tev.waitForStreamsEnded(1, 5));
  EXPECT_EQ(tev.packets(), 1);
  EXPECT_TRUE(tev.problems().empty());
}

TEST(TevConnection, RefusedConnectionSaysSo) {
  int fd = -1;
  const int port = unusedPort(fd);
  ASSERT_GT(port, 0);
  TevConnection c;
  std::string why;
  EXPECT_FALSE(c.connect(serverAt(port), 3, why));
  EXPECT_NE(why.find("refused"), std::string::npos) << why;
  ::close(fd);
}

TEST(TevConnection, PeerThatNeverReadsFailsTheEndOfStreamWithinItsTimeout) {
  FakeTev tev(FakeTev::Mode::NeverAccept);
  TevConnection c;
  std::string why;
  std::vector<uint8_t> packet;
  // The kernel accepts the connection into the backlog, and takes the packet, without tev accepting.
  ASSERT_NO_FATAL_FAILURE(connectAndSendOnePacket(tev, c, packet, why));
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_FALSE(c.finish(0.3, why));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
  EXPECT_NE(why.find("did not close"), std::string::npos) << why;
}

TEST(TevConnection, PeerThatClosedIsNoticed) {
  FakeTev tev(FakeTev::Mode::CloseAfterFirstPacket);
  TevConnection c;
  std::string why;
  std::vector<uint8_t> packet;
  ASSERT_NO_FATAL_FAILURE(connectAndSendOnePacket(tev, c, packet, why));
  ASSERT_TRUE(tev.waitForStreamsEnded(1, 5));
  bool noticed = false;  // by a write (the peer's reset) or by peerClosed; bounded either way
  for (int i = 0; i < 100 && !noticed; ++i) {
    noticed = c.peerClosed() || !c.write(packet, 1, why);
    if (!noticed) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(noticed);
}

}  // namespace
}  // namespace penumbra::net
