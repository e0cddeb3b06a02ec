#include "app/ui/display_tonemap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <random>

#include "core/image/tonemap.h"

using namespace penumbra;
using namespace penumbra::ui;

namespace {

float fromBits(std::uint32_t b) {
  float t;
  std::memcpy(&t, &b, sizeof t);
  return t;
}

}  // namespace

// The table equals its defining function for every float around every level change (±4096 ulps)
// and for a million random floats in [0, 2).
TEST(DisplayLevelTable, EqualsTheToneCurveExactly) {
  for (Tonemap curve : {Tonemap::Srgb, Tonemap::Gamma22}) {
    DisplayLevelTable table(curve);
    std::mt19937 rng(7);
    std::uniform_int_distribution<std::uint32_t> bits(0, 0x40000000u);
    for (int i = 0; i < 1000000; ++i) {
      float t = fromBits(bits(rng));
      ASSERT_EQ(table(t), DisplayLevelTable::reference(curve, t)) << t;
    }
    // Find each level change by bisection on the bit pattern, then check its neighbourhood.
    for (int level = 1; level <= 255; ++level) {
      std::uint32_t lo = 0, hi = 0x3F800000u;
      while (lo + 1 < hi) {
        std::uint32_t mid = lo + (hi - lo) / 2;
        (DisplayLevelTable::reference(curve, fromBits(mid)) < level ? lo : hi) = mid;
      }
      for (std::uint32_t b = hi - 4096; b <= hi + 4096; ++b)
        ASSERT_EQ(table(fromBits(b)), DisplayLevelTable::reference(curve, fromBits(b))) << fromBits(b);
    }
    EXPECT_EQ(table(0.f), 0);
    EXPECT_EQ(table(1.f), 255);
    EXPECT_EQ(table(std::numeric_limits<float>::infinity()), 255);
    EXPECT_EQ(table(std::numeric_limits<float>::denorm_min()), 0);
  }
}

// The colour view is toSrgb8 of the exposed image (what `penumbra render -o x.png` writes), NaN,
// Inf, negative and -0 pixels included, with the AVX2 loop (where the CPU has it) and without.
TEST(DisplayTonemap, ColourViewEqualsToSrgb8WithExposure) {
  Image img(67, 31);  // 2077 pixels: not a multiple of the SIMD loop's 4
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-0.1f, 1.2f);
  std::uniform_int_distribution<std::uint32_t> anyBits(0, ~0u);
  for (float& v : img.rgb) v = u(rng);
  for (size_t i = 0; i < img.rgb.size(); i += 7) img.rgb[i] *= 1e-3f;  // dark values, linear segment
  for (size_t i = 3; i < img.rgb.size(); i += 29) img.rgb[i] = fromBits(anyBits(rng));  // any float
  const float special[] = {std::numeric_limits<float>::quiet_NaN(),
                           std::numeric_limits<float>::infinity(),
                           std::numeric_limits<float>::max(),
                           -std::numeric_limits<float>::infinity(),
                           -0.f,
                           std::numeric_limits<float>::denorm_min(),
                           1.f,
                           0.99999994f};
  for (size_t i = 0; i < std::size(special); ++i) img.rgb[i * 5] = special[i];
  img.rgb.back() = std::numeric_limits<float>::quiet_NaN();  // in the tail
  DisplayLevelTable table(Tonemap::Srgb);
  for (bool simd : {true, false})
    for (PixelOrder order : {PixelOrder::Rgba, PixelOrder::Bgra})
      for (float exposure : {0.f, 1.5f, -3.25f, 10.f, 127.f}) {
        setDisplayTonemapSimd(simd);
        DisplaySettings d;
        d.exposure = exposure;
        std::vector<std::uint32_t> out;
        tonemapForDisplay(img, Image(), d, table, order, out);
        const std::uint8_t* px = reinterpret_cast<const std::uint8_t*>(out.data());
        std::vector<std::uint8_t> ref = toSrgb8(img, exposure);
        ASSERT_EQ(out.size(), size_t(img.width) * img.height);
        for (size_t p = 0; p < size_t(img.width) * img.height; ++p) {
          for (int c = 0; c < 3; ++c)
            ASSERT_EQ(px[p * 4 + (order == PixelOrder::Bgra ? 2 - c : c)], ref[p * 3 + c])
                << "pixel " << p << " value " << img.rgb[p * 3 + c] << " exposure " << exposure << " simd "
                << displayTonemapSimd();
          ASSERT_EQ(px[p * 4 + 3], 255);
        }
      }
  setDisplayTonemapSimd(true);
}

TEST(DisplayTonemap, FalseColourViews) {
  Image mean(4, 1), err(4, 1);
  float m[4] = {1.f, 1.f, std::numeric_limits<float>::quiet_NaN(), -0.5f};
  float e[4] = {0.001f, 1.f, 0.f, 0.f};
  for (int x = 0; x < 4; ++x)
    for (int c = 0; c < 3; ++c) mean.rgb[x * 3 + c] = m[x], err.rgb[x * 3 + c] = e[x];
  DisplaySettings d;
  d.falseColour = FalseColour::RelativeError;
  DisplayLevelTable table(Tonemap::Srgb);
  std::vector<std::uint32_t> out;
  const std::uint8_t* rgba = nullptr;
  auto tonemap = [&](const Image& e, PixelOrder order) {
    tonemapForDisplay(mean, e, d, table, order, out);
    rgba = reinterpret_cast<const std::uint8_t*>(out.data());
  };
  tonemap(err, PixelOrder::Rgba);
  EXPECT_EQ(rgba[0], 0);  // 0.1 %: blue
  EXPECT_EQ(rgba[1], 0);
  EXPECT_EQ(rgba[2], 255);
  EXPECT_EQ(rgba[4], 255);  // 100 %: red
  EXPECT_EQ(rgba[5], 0);
  EXPECT_EQ(rgba[6], 0);
  tonemap(Image(), PixelOrder::Rgba);  // no standard error yet: black
  EXPECT_EQ(rgba[0] + rgba[1] + rgba[2], 0);

  d.falseColour = FalseColour::BadPixels;
  tonemap(err, PixelOrder::Rgba);
  EXPECT_EQ(rgba[0], 153);  // white, dimmed to 60 %
  EXPECT_EQ(rgba[8], 255);  // NaN: magenta
  EXPECT_EQ(rgba[9], 0);
  EXPECT_EQ(rgba[10], 255);
  EXPECT_EQ(rgba[12], 0);  // negative: cyan
  EXPECT_EQ(rgba[13], 255);
  EXPECT_EQ(rgba[14], 255);
  tonemap(err, PixelOrder::Bgra);
  EXPECT_EQ(rgba[12], 255);  // cyan as BGRA
  EXPECT_EQ(rgba[13], 255);
  EXPECT_EQ(rgba[14], 0);
}
