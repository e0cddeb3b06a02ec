#include "app/net/tev_protocol.h"

#include <algorithm>
#include <bit>
#include <cstring>

#include "core/math/error.h"

namespace penumbra::net {

std::vector<TileRect> tevTiles(int width, int height, int tileSize) {
  std::vector<TileRect> tiles;
  if (width <= 0 || height <= 0 || tileSize <= 0) return tiles;
  for (int y = 0; y < height; y += tileSize)
    for (int x = 0; x < width; x += tileSize)
      tiles.push_back({x, y, std::min(tileSize, width - x), std::min(tileSize, height - y)});
  return tiles;
}

std::vector<std::string> tevChannelNames(std::span<const TevLayer> layers) {
  std::vector<std::string> names;
  for (const TevLayer& l : layers)
    for (const char* c : {"R", "G", "B"}) names.push_back(l.prefix + c);
  return names;
}

namespace {

// Little-endian writer into a packet whose first 4 bytes hold its length (set by finish()).
class PacketWriter {
 public:
  PacketWriter(std::vector<uint8_t>& out, TevPacketType type) : out_(out) {
    out_.clear();
    u32(0);
    out_.push_back(uint8_t(type));
  }
  void boolean(bool b) { out_.push_back(b ? 1 : 0); }
  void u32(uint32_t v) {
    for (int i = 0; i < 4; ++i) out_.push_back(uint8_t(v >> (8 * i)));
  }
  void i32(int32_t v) { u32(uint32_t(v)); }
  void string(std::string_view s) {
    out_.insert(out_.end(), s.begin(), s.end());
    out_.push_back(0);
  }
  // Room for n floats, written by f32At.
  size_t reserveFloats(size_t n) {
    size_t at = out_.size();
    out_.resize(at + 4 * n);
    return at;
  }
  void f32At(size_t at, float f) {
    const uint32_t v = std::bit_cast<uint32_t>(f);
    uint8_t* p = out_.data() + at;
    p[0] = uint8_t(v), p[1] = uint8_t(v >> 8), p[2] = uint8_t(v >> 16), p[3] = uint8_t(v >> 24);
  }
  void finish() {
    if (out_.size() > UINT32_MAX) throw Error("tev packet of " + std::to_string(out_.size()) + " bytes");
    const uint32_t n = uint32_t(out_.size());
    for (int i = 0; i < 4; ++i) out_[i] = uint8_t(n >> (8 * i));
  }

 private:
  std::vector<uint8_t>& out_;
};

// Bounds-checked little-endian reader of one packet.
class PacketReader {
 public:
  explicit PacketReader(std::span<const uint8_t> p) : p_(p) {}
  uint8_t byte(const char* what) {
    need(1, what);
    return p_[at_++];
  }
  bool boolean(const char* what) {
    uint8_t b = byte(what);
    if (b > 1) fail(std::string(what) + ": expected a bool (0 or 1), got " + std::to_string(b));
    return b == 1;
  }
  uint32_t u32(const char* what) {
    need(4, what);
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= uint32_t(p_[at_ + i]) << (8 * i);
    at_ += 4;
    return v;
  }
  int32_t i32(const char* what) { return int32_t(u32(what)); }
  float f32(const char* what) { return std::bit_cast<float>(u32(what)); }
  std::string string(const char* what) {
    const uint8_t* begin = p_.data() + at_;
    const void* nul = std::memchr(begin, 0, p_.size() - at_);
    if (!nul) fail(std::string(what) + ": expected a NUL-terminated string");
    std::string s(reinterpret_cast<const char*>(begin), static_cast<const uint8_t*>(nul) - begin);
    at_ += s.size() + 1;
    return s;
  }
  size_t remaining() const { return p_.size() - at_; }
  [[noreturn]] void fail(const std::string& what) const {
    throw Error("tev packet, byte " + std::to_string(at_) + ": " + what);
  }

 private:
  void need(size_t n, const char* what) {
    if (p_.size() - at_ < n) fail(std::string(what) + ": packet ends early");
  }
  std::span<const uint8_t> p_;
  size_t at_ = 0;
};

// Image sizes and channel counts a packet may claim (tev's own limits are larger; these catch garbage).
constexpr int32_t kMaxSide = 1 << 16, kMaxChannels = 1024;

int32_t positive(PacketReader& r, const char* what, int32_t max) {
  int32_t v = r.i32(what);
  if (v <= 0 || v > max)
    r.fail(std::string(what) + ": expected 1.." + std::to_string(max) + ", got " + std::to_string(v));
  return v;
}

std::vector<std::string> channelNames(PacketReader& r) {
  int32_t n = positive(r, "channel count", kMaxChannels);
  std::vector<std::string> names;
  for (int32_t i = 0; i < n; ++i) names.push_back(r.string("channel name"));
  return names;
}

}  // namespace

void encodeCreateImage(const TevCreateImage& p, std::vector<uint8_t>& out) {
  PacketWriter w(out, TevPacketType::CreateImage);
  w.boolean(p.grabFocus);
  w.string(p.name);
  w.i32(p.width);
  w.i32(p.height);
  w.i32(int32_t(p.channels.size()));
  for (const std::string& c : p.channels) w.string(c);
  w.finish();
}

void encodeUpdateImage(std::string_view name, bool grabFocus, std::span<const TevLayer> layers,
                       const TileRect& tile, std::vector<uint8_t>& out) {
  PacketWriter w(out, TevPacketType::UpdateImageV2);
  w.boolean(grabFocus);
  w.string(name);
  w.i32(int32_t(3 * layers.size()));
  for (const TevLayer& l : layers)
    for (const char* c : {"R", "G", "B"}) w.string(l.prefix + c);
  w.i32(tile.x);
  w.i32(tile.y);
  w.i32(tile.width);
  w.i32(tile.height);
  const size_t pixels = size_t(tile.width) * size_t(tile.height);
  size_t at = w.reserveFloats(3 * layers.size() * pixels);
  for (const TevLayer& l : layers) {
    const Image& img = *l.image;
    if (tile.x < 0 || tile.y < 0 || tile.x + tile.width > img.width || tile.y + tile.height > img.height)
      throw Error("tev update: tile outside the " + std::to_string(img.width) + "x" +
                  std::to_string(img.height) + " image of layer '" + l.prefix + "'");
    for (int c = 0; c < 3; ++c)
      for (int y = tile.y; y < tile.y + tile.height; ++y) {
        const float* row = &img.rgb[img.index(tile.x, y) + size_t(c)];
        for (int x = 0; x < tile.width; ++x, at += 4) w.f32At(at, row[3 * size_t(x)]);
      }
  }
  w.finish();
}

size_t tevPacketLength(std::span<const uint8_t> stream, size_t maxBytes) {
  if (stream.size() < 4) return 0;
  const size_t n =
      size_t(stream[0]) | size_t(stream[1]) << 8 | size_t(stream[2]) << 16 | size_t(stream[3]) << 24;
  if (n < 5 || n > maxBytes)
    throw Error("tev packet length " + std::to_string(n) + ": expected 5.." + std::to_string(maxBytes) +
                " bytes");
  return n;
}

TevPacket decodeTevPacket(std::span<const uint8_t> packet) {
  PacketReader r(packet);
  const uint32_t length = r.u32("length");
  if (length != packet.size())
    r.fail("length field says " + std::to_string(length) + " bytes, the packet has " +
           std::to_string(packet.size()));
  const uint8_t type = r.byte("type");
  if (type == uint8_t(TevPacketType::CreateImage)) {
    TevCreateImage c;
    c.grabFocus = r.boolean("grabFocus");
    c.name = r.string("image name");
    c.width = positive(r, "width", kMaxSide);
    c.height = positive(r, "height", kMaxSide);
    c.channels = channelNames(r);
    if (r.remaining() != 0) r.fail(std::to_string(r.remaining()) + " bytes after the last channel name");
    return c;
  }
  if (type == uint8_t(TevPacketType::UpdateImageV2)) {
    TevUpdateImage u;
    u.grabFocus = r.boolean("grabFocus");
    u.name = r.string("image name");
    u.channels = channelNames(r);
    u.tile.x = r.i32("tile x");
    u.tile.y = r.i32("tile y");
    u.tile.width = positive(r, "tile width", kMaxSide);
    u.tile.height = positive(r, "tile height", kMaxSide);
    if (u.tile.x < 0 || u.tile.y < 0) r.fail("tile origin: expected non-negative coordinates");
    const size_t floats = u.channels.size() * size_t(u.tile.width) * size_t(u.tile.height);
    if (r.remaining() != 4 * floats)
      r.fail("pixel data: expected " + std::to_string(4 * floats) +
             " bytes (channels x width x height floats), got " + std::to_string(r.remaining()));
    u.data.resize(floats);
    for (float& f : u.data) f = r.f32("pixel");
    return u;
  }
  r.fail("type " + std::to_string(type) + ": expected CreateImage (4) or UpdateImageV2 (5)");
}

}  // namespace penumbra::net
