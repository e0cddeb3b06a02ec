#include "app/ui/light_share_map.h"

#include <gtest/gtest.h>

#include "app/ui/display_tonemap.h"

namespace penumbra::ui {
namespace {

TEST(LightShareMap, EndsMiddleAndNoShare) {
  std::uint8_t rgb[3];
  lightShareRgb(0.f, rgb);
  EXPECT_EQ(rgb[0], kShareZeroRgb[0]);
  EXPECT_EQ(rgb[2], kShareZeroRgb[2]);
  lightShareRgb(0.5f, rgb);
  EXPECT_EQ(rgb[1], kShareHalfRgb[1]);
  lightShareRgb(1.f, rgb);
  EXPECT_EQ(rgb[0], kShareOneRgb[0]);
  EXPECT_EQ(rgb[1], kShareOneRgb[1]);
  lightShareRgb(-1.f, rgb);
  EXPECT_EQ(rgb[0], kNoShareRgb[0]);
}

// The PNG of the view (lightShareMapImage, written through toSrgb8) and the display's CPU tone
// mapping give the same 8-bit colours.
TEST(LightShareMap, ThePngImageAndTheDisplayAgree) {
  Image split(5, 1);
  split.set(0, 0, Color3(1.f, 0.f, 3.f));      // all light sampling
  split.set(1, 0, Color3(0.f, 2.f, 0.f));      // all cosine
  split.set(2, 0, Color3(0.25f, 0.75f, 0.f));  // 1/4
  split.set(3, 0, Color3(0.f, 0.f, 5.f));      // no area light
  split.set(4, 0, Color3(0.6f, 0.4f, 0.f));    // 0.6
  const Image png = lightShareMapImage(split);
  DisplaySettings d;
  d.falseColour = FalseColour::MisLightShare;
  d.exposure = 3.f;  // ignored by the map
  DisplayLevelTable table(Tonemap::Srgb);
  std::vector<std::uint32_t> pixels;
  tonemapForDisplay(split, Image(), d, table, PixelOrder::Rgba, pixels);
  for (int x = 0; x < 5; ++x) {
    const std::uint8_t* px = reinterpret_cast<const std::uint8_t*>(&pixels[x]);
    const Color3 c = png.at(x, 0);
    EXPECT_EQ(px[0], toSrgb8(c.x)) << x;
    EXPECT_EQ(px[1], toSrgb8(c.y)) << x;
    EXPECT_EQ(px[2], toSrgb8(c.z)) << x;
  }
  for (int level = 0; level < 256; ++level)  // every level survives the decode
    EXPECT_EQ(toSrgb8(srgbToLinear(level / 255.f)), level);
}

}  // namespace
}  // namespace penumbra::ui
