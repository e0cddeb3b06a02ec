#include "app/net/tev_streamer.h"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <unistd.h>

#include <string>
#include <vector>

#include "app/net/fake_tev.h"

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

}  // namespace
}  // namespace penumbra::net
