#include "core/image/image_io.h"
#include "core/math/temp_dir_test_support.h"

#include <gtest/gtest.h>
#include <png.h>

#include <unistd.h>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <limits>

#include "core/image/tonemap.h"
#include "core/math/error.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

class ImageIoTest : public test::TempDirTest {
 protected:
  ImageIoTest() : TempDirTest("penumbra-image-io-") {}
};

// Non-square with distinct values everywhere, plus the awkward floats.
Image testImage(int w = 7, int h = 5) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img.set(x, y, Color3(x + 0.25f, y * 10.f + 0.5f, -0.125f * (x + 1) * (y + 1)));
  img.set(0, 0, Color3(std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::max(), 1e-30f));
  img.set(w - 1, h - 1, Color3(300.f, 0.1f, 3.14159265f));
  img.set(1, 0,
          Color3(std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                 -std::numeric_limits<float>::infinity()));
  return img;
}

void expectBitwiseEqual(const Image& a, const Image& b) {
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  EXPECT_EQ(std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)), 0);
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST_F(ImageIoTest, ExrRoundTripIsExact) {
  Image img = testImage();
  writeImage(file("a.exr"), img);
  expectBitwiseEqual(readImage(file("a.exr")), img);
}

TEST_F(ImageIoTest, ExrMetadataRoundTrip) {
  ImageMetadata meta;
  meta.add("spp", "1024");
  meta.add("seconds", "12.5");
  meta.add("integrator", "path maxDepth=8 rr=on");
  meta.add("seed", "42");
  writeImage(file("m.exr"), testImage(), meta);
  ImageMetadata back = readImageMetadata(file("m.exr"));
  for (const auto& [k, v] : meta.entries) {
    ASSERT_NE(back.find(k), nullptr) << k;
    EXPECT_EQ(*back.find(k), v);
  }
  ImageMetadata viaRead;
  Image img = readExr(file("m.exr"), &viaRead);
  EXPECT_EQ(img.width, 7);
  ASSERT_NE(viaRead.find("integrator"), nullptr);
  EXPECT_EQ(*viaRead.find("integrator"), "path maxDepth=8 rr=on");
}

TEST_F(ImageIoTest, ExrMetadataClashingWithStandardAttributeThrows) {
  ImageMetadata meta;
  meta.add("compression", "none");
  EXPECT_THROW(writeImage(file("c.exr"), testImage(), meta), Error);
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST_F(ImageIoTest, ExrHalfInputIsRead) {
  Image img(4, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) img.set(x, y, Color3(0.5f * x, 0.25f * y, 300.f));  // exact in half
  writeExr(file("h.exr"), img, {}, ExrPixelType::Half);
  expectBitwiseEqual(readImage(file("h.exr")), img);
  Image rounded(1, 1);
  rounded.set(0, 0, Color3(0.1f, 1.f / 3.f, 1000.3f));
  writeExr(file("h2.exr"), rounded, {}, ExrPixelType::Half);
  Color3 c = readImage(file("h2.exr")).at(0, 0);
  EXPECT_NEAR(c.x, 0.1f, 0.1f / 1024);
  EXPECT_NEAR(c.y, 1.f / 3.f, 1.f / 3072);
  EXPECT_NEAR(c.z, 1000.3f, 1000.f / 1024);
}

TEST_F(ImageIoTest, PfmRoundTripIsExact) {
  Image img = testImage();
  writeImage(file("a.pfm"), img);
  expectBitwiseEqual(readImage(file("a.pfm")), img);
  EXPECT_TRUE(readImageMetadata(file("a.pfm")).entries.empty());
}

TEST_F(ImageIoTest, PfmByteLayoutIsBottomRowFirstLittleEndian) {
  Image img(2, 2);
  img.set(0, 0, Color3(1, 2, 3));  // top row
  img.set(1, 0, Color3(4, 5, 6));
  img.set(0, 1, Color3(7, 8, 9));  // bottom row
  img.set(1, 1, Color3(10, 11, 12));
  writePfm(file("l.pfm"), img);
  const std::string bytes = readFile(file("l.pfm"));
  const std::string header = "PF\n2 2\n-1.0\n";
  ASSERT_EQ(bytes.size(), header.size() + 12 * 4);
  EXPECT_EQ(bytes.substr(0, header.size()), header);
  const float expected[12] = {7, 8, 9, 10, 11, 12, 1, 2, 3, 4, 5, 6};
  for (int i = 0; i < 12; ++i) {
    const unsigned char* p = reinterpret_cast<const unsigned char*>(bytes.data() + header.size() + 4 * i);
    std::uint32_t u = p[0] | (p[1] << 8) | (p[2] << 16) | (std::uint32_t(p[3]) << 24);  // little-endian
    float f;
    std::memcpy(&f, &u, 4);
    EXPECT_EQ(f, expected[i]) << i;
  }
}

TEST_F(ImageIoTest, PfmReadsBigEndianAndGreyscale) {
  // Big-endian colour, 1x2 (bottom row first), positive scale.
  auto be = [](float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    return std::string{char(u >> 24), char(u >> 16), char(u >> 8), char(u)};
  };
  {
    std::ofstream out(file("be.pfm"), std::ios::binary);
    out << "PF\n1 2\n1.0\n" << be(1) << be(2) << be(3) << be(4) << be(5) << be(6);
  }
  Image img = readImage(file("be.pfm"));
  ASSERT_EQ(img.width, 1);
  ASSERT_EQ(img.height, 2);
  EXPECT_EQ(img.at(0, 1), Color3(1, 2, 3));
  EXPECT_EQ(img.at(0, 0), Color3(4, 5, 6));
  {
    std::ofstream out(file("g.pfm"), std::ios::binary);
    const float v[2] = {0.5f, -2.f};  // little-endian host assumed by this test's writer
    out << "Pf\n2 1\n-1.0\n";
    out.write(reinterpret_cast<const char*>(v), sizeof v);
  }
  Image g = readImage(file("g.pfm"));
  EXPECT_EQ(g.at(0, 0), Color3(0.5f));
  EXPECT_EQ(g.at(1, 0), Color3(-2.f));
}

TEST_F(ImageIoTest, PfmRejectsTruncatedAndGarbage) {
  {
    std::ofstream out(file("t.pfm"), std::ios::binary);
    out << "PF\n4 4\n-1.0\n" << std::string(10, '\0');
  }
  EXPECT_THROW(readImage(file("t.pfm")), Error);
  {
    std::ofstream out(file("x.pfm"), std::ios::binary);
    out << "P6\n4 4\n255\n";
  }
  EXPECT_THROW(readImage(file("x.pfm")), Error);
  EXPECT_THROW(readImage(file("missing.pfm")), Error);
}

TEST_F(ImageIoTest, PngMatchesToSrgb8ViaLibpng) {
  Image img(5, 3);
  const float values[] = {0.f, 0.001f, 0.0031308f, 0.02f, 0.18f, 0.5f, 0.99f, 1.f, 7.f, -1.f};
  for (int i = 0; i < 15; ++i)
    img.rgb[3 * i] = values[i % 10], img.rgb[3 * i + 1] = values[(i + 3) % 10],
                img.rgb[3 * i + 2] = values[(i + 7) % 10];
  img.set(4, 2,
          Color3(std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), 0.5f));
  for (float stops : {0.f, 1.5f, -2.f}) {
    writeImage(file("a.png"), img, {}, stops);
    png_image png;
    std::memset(&png, 0, sizeof png);
    png.version = PNG_IMAGE_VERSION;
    ASSERT_TRUE(png_image_begin_read_from_file(&png, file("a.png").c_str()));
    EXPECT_EQ(png.width, 5u);
    EXPECT_EQ(png.height, 3u);
    png.format = PNG_FORMAT_RGB;
    std::vector<std::uint8_t> bytes(PNG_IMAGE_SIZE(png));
    ASSERT_TRUE(png_image_finish_read(&png, nullptr, bytes.data(), 0, nullptr));
    EXPECT_EQ(bytes, toSrgb8(img, stops)) << stops;
  }
  // NaN and Inf become 0.
  auto b = toSrgb8(img);
  EXPECT_EQ(b[3 * 14 + 0], 0);
  EXPECT_EQ(b[3 * 14 + 1], 0);
  // Reading back decodes to linear; re-encoding reproduces the bytes.
  writeImage(file("b.png"), img);
  EXPECT_EQ(toSrgb8(readImage(file("b.png"))), toSrgb8(img));
}

TEST_F(ImageIoTest, UnsupportedExtensionListsSupportedOnes) {
  try {
    writeImage(file("a.jpg"), testImage());
    FAIL() << "expected Error";
  } catch (const Error& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find(".exr"), std::string::npos);
    EXPECT_NE(msg.find(".pfm"), std::string::npos);
    EXPECT_NE(msg.find(".png"), std::string::npos);
  }
  EXPECT_THROW(readImage(file("noext")), Error);
  EXPECT_TRUE(fs::is_empty(dir));
  // Extension matching is case-insensitive.
  writeImage(file("UP.EXR"), testImage());
  EXPECT_TRUE(fs::exists(file("UP.EXR")));
}

// The system would read or write such a path only up to its NUL byte: another file.
TEST_F(ImageIoTest, PathsWithANulByteAreRefused) {
  for (const char* ext : {".exr", ".pfm", ".png"}) {
    writeImage(file(std::string("a") + ext), testImage());
    const std::string withNul = file(std::string("a") + ext) + '\0' + ".old" + ext;
    try {
      readImage(withNul);
      ADD_FAILURE() << "read " << ext;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("has a NUL byte at offset"), std::string::npos) << e.what();
    }
    const auto before = fs::last_write_time(file(std::string("a") + ext));
    EXPECT_THROW(writeImage(withNul, testImage(3, 2)), Error) << ext;
    EXPECT_EQ(fs::last_write_time(file(std::string("a") + ext)), before) << ext;
  }
}

TEST_F(ImageIoTest, EmptyImageThrows) {
  EXPECT_THROW(writeImage(file("e.exr"), Image{}), Error);
  Image bad(2, 2);
  bad.rgb.pop_back();
  EXPECT_THROW(writeImage(file("e.pfm"), bad), Error);
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(ImageIoReference, ReadsTheAssignmentsReferenceExr) {
  const std::string path = PENUMBRA_SOURCE_DIR "/scenes/hw2/References/sphere-area.exr";
  if (!fs::exists(path)) GTEST_SKIP() << "the assignment's scenes not found at " << path;
  Image img = readImage(path);
  ASSERT_EQ(img.width, 768);
  ASSERT_EQ(img.height, 768);
  double sum = 0;
  float maxValue = 0;
  for (float v : img.rgb) {
    ASSERT_TRUE(std::isfinite(v));
    sum += v;
    maxValue = std::max(maxValue, v);
  }
  EXPECT_NEAR(sum / img.rgb.size(), 0.555, 0.005);
  std::size_t lightPixels = 0;
  for (std::size_t i = 0; i < img.rgb.size(); i += 3)
    if (img.rgb[i] > 299.f && img.rgb[i + 1] > 299.f && img.rgb[i + 2] > 299.f) ++lightPixels;
  EXPECT_NEAR(maxValue, 300.f, 0.01f) << std::setprecision(9) << maxValue;  // the light
  EXPECT_GT(lightPixels, 0u);
}

// Headers that declare more than the file holds: OpenEXR would allocate what they declare (a 3 GB
// attribute from a 400-byte file) before noticing.
TEST_F(ImageIoTest, ExrHeadersDeclaringMoreThanTheFileHoldsAreRefusedFirst) {
  // Inputs the fuzzer found: an attribute of 3 GB, and a channel list longer than its declared size
  // (OpenEXR reads it to its terminator, then takes string bytes as a huge attribute size).
  const std::string regressions = std::string(PENUMBRA_SOURCE_DIR) + "/fuzz/regressions/";
  for (const char* name :
       {"exr-attribute-larger-than-file.exr", "exr-channel-list-longer-than-declared.exr"}) {
    for (auto read :
         {+[](const std::string& p) { readExr(p); }, +[](const std::string& p) { readExrMetadata(p); }}) {
      try {
        read(regressions + name);
        FAIL() << "accepted " << name;
      } catch (const Error& e) {
        const std::string m = e.what();
        EXPECT_TRUE(m.find("declares") != std::string::npos ||
                    m.find("does not match") != std::string::npos ||
                    m.find("data window") != std::string::npos)
            << m;
      }
    }
  }
  // A valid file whose data window is patched to 2^20 x 2^20 pixels.
  writeImage(file("small.exr"), testImage());
  std::string bytes = readFile(file("small.exr"));
  const size_t at = bytes.find(std::string("dataWindow\0box2i\0", 17));
  ASSERT_NE(at, std::string::npos);
  const int32_t box[4] = {0, 0, (1 << 20) - 1, (1 << 20) - 1};
  std::memcpy(&bytes[at + 17 + 4], box, 16);
  std::ofstream(file("huge.exr"), std::ios::binary) << bytes;
  try {
    readExr(file("huge.exr"));
    FAIL() << "accepted a 2^40-pixel data window";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("data window"), std::string::npos) << e.what();
  }
  EXPECT_THROW(readExr("/dev/zero"), Error);
}

// Files whose chunk offset table cannot cover their data window (found by the fuzzer: a valid small
// image's window patched to 2^20 x 64 pixels, 4 ZIP chunks whose offsets point at pixel data; and a
// tiled one patched to 8192 x 8192). Both are refused from the chunk table, before memory for the
// window is allocated: the C++ library alone allocated and filled ~400 MB first (1.4 s).
TEST_F(ImageIoTest, ExrWhoseChunksCannotCoverItsDataWindowIsRefusedBeforeAllocating) {
  const std::string regressions = std::string(PENUMBRA_SOURCE_DIR) + "/fuzz/regressions/";
  for (const char* name :
       {"exr-window-larger-than-its-chunks.exr", "exr-tiled-window-larger-than-its-tiles.exr"}) {
    try {
      readExr(regressions + name);
      FAIL() << "read " << name;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("incomplete or corrupt"), std::string::npos) << e.what();
    }
  }
}

// The chunk check walks tiles as well as scan lines: a valid tiled file (5 x 3 pixels in 2 x 2 ZIP
// tiles, half floats, the fuzzer's seed without its format byte) reads with its pixels.
TEST_F(ImageIoTest, TiledExrIsRead) {
  const std::string seed =
      readFile(std::string(PENUMBRA_SOURCE_DIR) + "/fuzz/corpus/image_fuzzer/rgb-5x3-tiled-zip.exr");
  ASSERT_GT(seed.size(), 1u);
  std::ofstream(file("tiled.exr"), std::ios::binary) << seed.substr(1);
  const Image image = readExr(file("tiled.exr"));
  ASSERT_EQ(image.width, 5);
  ASSERT_EQ(image.height, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) {
      const Color3 c = image.at(x, y);
      EXPECT_EQ(c.x, 0.25f * x);
      EXPECT_EQ(c.y, 0.5f * y);
      EXPECT_EQ(c.z, 1.f);
    }
}

// A data window far from the origin (found by the fuzzer): the reader's slice pointers must not be
// computed by offsetting a pointer that far, which is undefined behaviour (the sanitizer job's UBSan
// reports it; OpenEXR's Slice::Make offsets in integer arithmetic).
TEST_F(ImageIoTest, ExrDataWindowFarFromTheOriginIsReadWithoutUndefinedBehaviour) {
  try {  // an image or an Error, but no undefined behaviour
    readExr(std::string(PENUMBRA_SOURCE_DIR) + "/fuzz/regressions/exr-data-window-far-from-origin.exr");
  } catch (const Error&) {
  }
}

// A data window whose width and height are each near 2^32: their product overflows 64-bit integers,
// so the size check must not multiply them (UBSan reports the overflow in the sanitizer job).
TEST_F(ImageIoTest, ExrDataWindowWhoseAreaOverflowsIsRefused) {
  try {
    readExr(std::string(PENUMBRA_SOURCE_DIR) + "/fuzz/regressions/exr-data-window-area-overflows.exr");
    FAIL() << "an EXR with a 3430119579 x 3580943328 data window was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("data window"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace penumbra
