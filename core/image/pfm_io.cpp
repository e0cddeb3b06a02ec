// Portable float map: "PF\n<w> <h>\n<scale>\n" then raw 32-bit floats, bottom row first; a negative
// scale means little-endian. We always write little-endian with scale -1.0; the reader accepts both
// byte orders and greyscale "Pf" (replicated to RGB). |scale| is not applied (it is a unit hint).
#include <bit>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "core/image/atomic_file.h"
#include "core/image/image_io.h"
#include "core/math/bounded_read.h"
#include "core/math/error.h"

namespace penumbra {

namespace {

constexpr bool kHostLittle = std::endian::native == std::endian::little;

std::uint32_t byteSwap(std::uint32_t v) {
  return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

// Header tokenizer over the raw bytes; PFM headers are whitespace separated ASCII.
struct HeaderReader {
  const std::vector<char>& bytes;
  const std::string& path;
  std::size_t pos = 0;

  std::string token() {
    while (pos < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
    std::size_t start = pos;
    while (pos < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
    if (start == pos) throw Error(path, 0, "truncated PFM header");
    return std::string(bytes.data() + start, pos - start);
  }
};

}  // namespace

void writePfm(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 || image.rgb.size() != image.pixelCount() * 3)
    throw Error(path, 0, "cannot write an empty or inconsistent image");
  std::string header = "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
  std::vector<char> bytes(header.begin(), header.end());
  const std::size_t rowFloats = static_cast<std::size_t>(image.width) * 3;
  bytes.reserve(header.size() + image.rgb.size() * 4);
  for (int y = image.height - 1; y >= 0; --y) {
    const float* row = image.rgb.data() + static_cast<std::size_t>(y) * rowFloats;
    for (std::size_t i = 0; i < rowFloats; ++i) {
      std::uint32_t u = std::bit_cast<std::uint32_t>(row[i]);
      if (!kHostLittle) u = byteSwap(u);
      char b[4];
      std::memcpy(b, &u, 4);
      bytes.insert(bytes.end(), b, b + 4);
    }
  }
  writeBytesAtomically(path, bytes.data(), bytes.size());
}

Image readPfm(const std::string& path) {
  checkRegularFile(path, kMaxImageFileBytes, "PFM file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, 0, std::string("cannot open: ") + std::strerror(errno));
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw Error(path, 0, "read error");

  HeaderReader h{bytes, path};
  std::string magic = h.token();
  int channels = 0;
  if (magic == "PF")
    channels = 3;
  else if (magic == "Pf")
    channels = 1;
  else
    throw Error(path, 0, "not a PFM file (magic '" + magic.substr(0, 8) + "')");
  long width = 0, height = 0;
  double scale = 0;
  try {
    std::string w = h.token(), hh = h.token(), s = h.token();
    std::size_t used = 0;
    width = std::stol(w, &used);
    if (used != w.size()) throw std::invalid_argument(w);
    height = std::stol(hh, &used);
    if (used != hh.size()) throw std::invalid_argument(hh);
    scale = std::stod(s, &used);
    if (used != s.size()) throw std::invalid_argument(s);
  } catch (const Error&) {
    throw;
  } catch (const std::exception&) {
    throw Error(path, 0, "malformed PFM header");
  }
  if (width <= 0 || height <= 0 || width > (1 << 20) || height > (1 << 20) || width * height > kMaxReadPixels)
    throw Error(path, 0, "bad PFM size " + std::to_string(width) + "x" + std::to_string(height));
  if (scale == 0 || !std::isfinite(scale)) throw Error(path, 0, "bad PFM scale (must be nonzero)");
  // Exactly one whitespace character separates the header from the data.
  if (h.pos >= bytes.size() || !std::isspace(static_cast<unsigned char>(bytes[h.pos])))
    throw Error(path, 0, "truncated PFM header");
  std::size_t dataStart = h.pos + 1;
  const bool fileLittle = scale < 0;
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * channels;
  if (bytes.size() - dataStart < count * 4)
    throw Error(path, 0,
                "truncated PFM data: expected " + std::to_string(count * 4) + " bytes, found " +
                    std::to_string(bytes.size() - dataStart));

  Image image(static_cast<int>(width), static_cast<int>(height));
  const char* src = bytes.data() + dataStart;
  for (long fy = 0; fy < height; ++fy) {
    const long y = height - 1 - fy;  // file stores the bottom row first
    for (long x = 0; x < width; ++x) {
      for (int c = 0; c < channels; ++c) {
        std::uint32_t u;
        std::memcpy(&u, src, 4);
        src += 4;
        if (fileLittle != kHostLittle) u = byteSwap(u);
        float v = std::bit_cast<float>(u);
        std::size_t i = image.index(static_cast<int>(x), static_cast<int>(y));
        if (channels == 3)
          image.rgb[i + c] = v;
        else
          image.rgb[i] = image.rgb[i + 1] = image.rgb[i + 2] = v;
      }
    }
  }
  return image;
}

}  // namespace penumbra
