// The packets of tev's network protocol (the image viewer github.com/Tom94/tev), as pure functions:
// encoding what Penumbra sends, decoding it again (the tests' fake tev), and the tiling of an image.
//
// Protocol (tev's README, "Over the Network", and the IpcPacket::set* functions of its src/Ipc.cpp):
// every packet is [uint32 total length in bytes, this field included][uint8 type][payload]; integers
// and floats are little endian, a bool is one byte (0/1), a string is its bytes and a NUL. Types used:
//   CreateImage   (4): bool grabFocus, string name, int32 width, int32 height, int32 nChannels,
//                      nChannels x string channel name. Replaces an open image of the same name.
//   UpdateImageV2 (5): bool grabFocus, string name, int32 nChannels, nChannels x string channel name,
//                      int32 x, y, width, height (the tile), then nChannels x width*height float32:
//                      channel after channel, each row-major over the tile, top row first.
// Why these two: tev has accepted CreateImage since v1.16 (2020) and UpdateImageV2 since v1.17
// (February 2021, also when it moved to TCP), and still does; UpdateImageV3 (6, v1.18) only adds
// per-channel offsets and strides, which planar tiles do not need, and UpdateImage (3) carries one
// channel per packet. Channel names follow the EXR "layer.channel" convention, which tev groups:
// "R","G","B" show as the image's colour, "stderr.R","stderr.G","stderr.B" as its "stderr" layer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/image/image.h"

namespace penumbra::net {

inline constexpr uint16_t kTevDefaultPort = 14158;  // tev listens on 127.0.0.1:14158 unless told otherwise
inline constexpr int kTevTileSize = 128;            // pixels per tile side (~390 KB per 6-channel packet)

enum class TevPacketType : uint8_t { CreateImage = 4, UpdateImageV2 = 5 };

struct TileRect {
  int x = 0, y = 0, width = 0, height = 0;
  bool operator==(const TileRect&) const = default;
};

// Row-major tiles of at most tileSize x tileSize that cover a width x height image exactly once.
std::vector<TileRect> tevTiles(int width, int height, int tileSize = kTevTileSize);

// Three channels of a tev image taken from an RGB image: prefix + "R", "G", "B".
struct TevLayer {
  std::string prefix;  // "" for the colour, e.g. "stderr." for a layer
  const Image* image = nullptr;
};
// Channel names of layers, in packet order.
std::vector<std::string> tevChannelNames(std::span<const TevLayer> layers);

struct TevCreateImage {
  bool grabFocus = false;
  std::string name;
  int32_t width = 0, height = 0;
  std::vector<std::string> channels;
};

struct TevUpdateImage {
  bool grabFocus = false;
  std::string name;
  std::vector<std::string> channels;
  TileRect tile;
  std::vector<float> data;                        // channels.size() planes of tile.width * tile.height floats
  float at(size_t channel, int x, int y) const {  // x, y relative to the tile
    return data[(channel * size_t(tile.height) + size_t(y)) * size_t(tile.width) + size_t(x)];
  }
};

using TevPacket = std::variant<TevCreateImage, TevUpdateImage>;

// Encoders replace `out`'s contents with one complete packet (reusing its capacity).
void encodeCreateImage(const TevCreateImage& packet, std::vector<uint8_t>& out);
// One tile of every layer (each layer's image must cover the tile). Its channels: tevChannelNames.
void encodeUpdateImage(std::string_view name, bool grabFocus, std::span<const TevLayer> layers,
                       const TileRect& tile, std::vector<uint8_t>& out);

// Length of the packet at the start of a byte stream: 0 while its 4-byte length is incomplete.
// Throws penumbra::Error when the length cannot be a packet's (below 5 bytes or above maxBytes).
size_t tevPacketLength(std::span<const uint8_t> stream, size_t maxBytes = size_t(1) << 30);
// One complete packet (exactly tevPacketLength bytes). Throws penumbra::Error, naming what was
// expected, on an unknown type, a length that disagrees with the contents, or impossible sizes.
TevPacket decodeTevPacket(std::span<const uint8_t> packet);

}  // namespace penumbra::net
