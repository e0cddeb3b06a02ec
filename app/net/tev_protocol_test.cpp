#include "app/net/tev_protocol.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/math/error.h"

namespace penumbra::net {
namespace {

// Bytes written out by hand from tev's description of the packets (tev_protocol.h), not by the encoder.
const std::vector<uint8_t> kCreateAb = {
    25,  0,   0,   0,  // total length
    4,                 // CreateImage
    1,                 // grabFocus
    'a', 'b', 0,       // name
    3,   0,   0,   0,  // width
    2,   0,   0,   0,  // height
    2,   0,   0,   0,  // channels
    'R', 0,   'G', 0,
};

const std::vector<uint8_t> kUpdateX = {
    58,  0, 0,    0,             // total length
    5,                           // UpdateImageV2
    0,                           // grabFocus
    'x', 0,                      // name
    3,   0, 0,    0,             // channels
    'R', 0, 'G',  0,    'B', 0,  //
    0,   0, 0,    0,             // x
    0,   0, 0,    0,             // y
    2,   0, 0,    0,             // width
    1,   0, 0,    0,             // height
    0,   0, 0x80, 0x3f,          // R: 1, 4
    0,   0, 0x80, 0x40,          //
    0,   0, 0,    0x40,          // G: 2, 5
    0,   0, 0xa0, 0x40,          //
    0,   0, 0x40, 0x40,          // B: 3, 6
    0,   0, 0xc0, 0x40,
};

TEST(TevProtocol, CreateImageMatchesTheDocumentedBytes) {
  std::vector<uint8_t> out;
  encodeCreateImage({true, "ab", 3, 2, {"R", "G"}}, out);
  EXPECT_EQ(out, kCreateAb);
  const auto c = std::get<TevCreateImage>(decodeTevPacket(kCreateAb));
  EXPECT_TRUE(c.grabFocus);
  EXPECT_EQ(c.name, "ab");
  EXPECT_EQ(c.width, 3);
  EXPECT_EQ(c.height, 2);
  EXPECT_EQ(c.channels, (std::vector<std::string>{"R", "G"}));
}

TEST(TevProtocol, UpdateImageIsPlanarChannelAfterChannel) {
  Image img(2, 1);
  img.set(0, 0, Color3(1, 2, 3));
  img.set(1, 0, Color3(4, 5, 6));
  const TevLayer layers[] = {{"", &img}};
  std::vector<uint8_t> out;
  encodeUpdateImage("x", false, layers, {0, 0, 2, 1}, out);
  EXPECT_EQ(out, kUpdateX);
  const auto u = std::get<TevUpdateImage>(decodeTevPacket(kUpdateX));
  EXPECT_EQ(u.channels, (std::vector<std::string>{"R", "G", "B"}));
  EXPECT_EQ(u.tile, (TileRect{0, 0, 2, 1}));
  EXPECT_EQ(u.data, (std::vector<float>{1, 4, 2, 5, 3, 6}));
}

TEST(TevProtocol, TilesOfLayersRoundTripFromAnyOffset) {
  Image mean(7, 5), err(7, 5);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x) {
      mean.set(x, y, Color3(float(x), float(y), float(x * y)));
      err.set(x, y, Color3(-float(x), std::nanf(""), 1e30f));
    }
  const TevLayer layers[] = {{"", &mean}, {"stderr.", &err}};
  EXPECT_EQ(tevChannelNames(layers),
            (std::vector<std::string>{"R", "G", "B", "stderr.R", "stderr.G", "stderr.B"}));
  std::vector<uint8_t> out;
  const TileRect tile{3, 1, 4, 3};
  encodeUpdateImage("img", true, layers, tile, out);
  ASSERT_EQ(tevPacketLength(out), out.size());
  const auto u = std::get<TevUpdateImage>(decodeTevPacket(out));
  EXPECT_TRUE(u.grabFocus);
  EXPECT_EQ(u.channels, tevChannelNames(layers));
  for (int y = 0; y < tile.height; ++y)
    for (int x = 0; x < tile.width; ++x)
      for (size_t c = 0; c < 6; ++c) {
        const Image& src = c < 3 ? mean : err;
        const float want = src.rgb[src.index(tile.x + x, tile.y + y) + c % 3];
        const float got = u.at(c, x, y);
        EXPECT_TRUE(got == want || (std::isnan(got) && std::isnan(want))) << c << " " << x << "," << y;
      }
  // A tile reaching outside a layer's image is refused, not read out of bounds.
  EXPECT_THROW(encodeUpdateImage("img", false, layers, {4, 0, 4, 1}, out), Error);
}

TEST(TevProtocol, TilesCoverTheImageExactlyOnce) {
  for (auto [w, h] :
       std::vector<std::pair<int, int>>{{1, 1}, {128, 128}, {129, 300}, {768, 768}, {200, 150}}) {
    std::vector<int> covered(size_t(w) * h, 0);
    for (const TileRect& t : tevTiles(w, h)) {
      EXPECT_GT(t.width, 0);
      EXPECT_LE(t.width, kTevTileSize);
      EXPECT_LE(t.height, kTevTileSize);
      for (int y = t.y; y < t.y + t.height; ++y)
        for (int x = t.x; x < t.x + t.width; ++x) ++covered[size_t(y) * w + x];
    }
    for (int c : covered) ASSERT_EQ(c, 1) << w << "x" << h;
  }
  EXPECT_TRUE(tevTiles(0, 5).empty());
  EXPECT_EQ(tevTiles(300, 10).size(), 3u);
}

TEST(TevProtocol, PacketLengthFramesAByteStream) {
  EXPECT_EQ(tevPacketLength(std::span(kCreateAb).first(3)), 0u);  // length incomplete
  EXPECT_EQ(tevPacketLength(kCreateAb), 25u);
  EXPECT_EQ(tevPacketLength(std::span(kCreateAb).first(4)), 25u);  // known before the rest arrives
  EXPECT_THROW(tevPacketLength(std::vector<uint8_t>{4, 0, 0, 0}), Error);
  EXPECT_THROW(tevPacketLength(std::vector<uint8_t>{0, 0, 0, 0x80}), Error);
}

TEST(TevProtocol, MalformedPacketsAreRejected) {
  auto with = [](std::vector<uint8_t> p, size_t at, uint8_t v) {
    p[at] = v;
    return p;
  };
  auto shorter = [](std::vector<uint8_t> p) {
    p.pop_back();
    p[0] = uint8_t(p.size());
    return p;
  };
  EXPECT_THROW(decodeTevPacket(with(kCreateAb, 0, 24)), Error);               // length field disagrees
  EXPECT_THROW(decodeTevPacket(with(kCreateAb, 4, 3)), Error);                // UpdateImage (v1): not ours
  EXPECT_THROW(decodeTevPacket(with(kCreateAb, 5, 2)), Error);                // a bool that is not 0 or 1
  EXPECT_THROW(decodeTevPacket(with(kCreateAb, 9, 0)), Error);                // width 0
  EXPECT_THROW(decodeTevPacket(with(kCreateAb, 17, 3)), Error);               // 3 channel names, 2 present
  EXPECT_THROW(decodeTevPacket(shorter(kCreateAb)), Error);                   // last name without its NUL
  EXPECT_THROW(decodeTevPacket(shorter(kUpdateX)), Error);                    // pixel data short
  EXPECT_THROW(decodeTevPacket(with(kUpdateX, 26, 3)), Error);                // width 3: data for 2
  EXPECT_THROW(decodeTevPacket(std::vector<uint8_t>{5, 0, 0, 0, 4}), Error);  // ends after the type
}

}  // namespace
}  // namespace penumbra::net
