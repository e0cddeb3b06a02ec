#include "app/ui/image_layout.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace penumbra::ui {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

TEST(ImageLayout, PixelUnderTheCursorAtOrdinaryZooms) {
  ImageLayout l{100.f, 50.f, 2.f, 320, 240};
  int px = -1, py = -1;
  ASSERT_TRUE(imagePixelAt(l, 100.f, 50.f, px, py));
  EXPECT_EQ(px, 0);
  EXPECT_EQ(py, 0);
  ASSERT_TRUE(imagePixelAt(l, 100.f + 2 * 319 + 1.9f, 50.f + 2 * 239 + 1.9f, px, py));
  EXPECT_EQ(px, 319);
  EXPECT_EQ(py, 239);
  EXPECT_FALSE(imagePixelAt(l, 99.9f, 60.f, px, py));
  EXPECT_FALSE(imagePixelAt(l, 100.f + 2 * 320, 60.f, px, py));
}

// The viewer converted (cursor - x) / zoom to int before comparing: at a zoom of ~1e-12 that was
// ~1e14, undefined behaviour (UBSan: "outside the range of representable values of type 'int'").
TEST(ImageLayout, NoPixelForQuotientsBeyondAnIntOrNotANumber) {
  int px = 7, py = 7;
  EXPECT_FALSE(imagePixelAt(ImageLayout{0.f, 0.f, 1e-12f, 320, 240}, 1047.f, 1.5f, px, py));
  EXPECT_FALSE(imagePixelAt(ImageLayout{-1e30f, 0.f, 1.f, 320, 240}, 0.f, 0.f, px, py));
  EXPECT_FALSE(imagePixelAt(ImageLayout{0.f, 0.f, 0.f, 320, 240}, 1.f, 1.f, px, py));
  EXPECT_FALSE(imagePixelAt(ImageLayout{0.f, 0.f, 1.f, 320, 240}, kNaN, 1.f, px, py));
  EXPECT_FALSE(imagePixelAt(ImageLayout{0.f, 0.f, 1.f, 320, 240}, kInf, kInf, px, py));
  EXPECT_EQ(px, 7);
  EXPECT_EQ(py, 7);
}

// A wheel event of -120 steps while fitting made the zoom 1.25^-120 ~ 2e-12 (the fitted branch was
// not clamped): every wheel value now lands in the offered range.
TEST(ImageLayout, WheelZoomStaysInRangeForAnyWheel) {
  for (bool fit : {false, true})
    for (float wheel : {-1e30f, -120.f, -1.f, 0.f, 1.f, 120.f, 1e30f, kInf, -kInf, kNaN}) {
      DisplaySettings d;
      d.fit = fit;
      d.zoom = 1.f;
      const float z = zoomAfterWheel(d, 0.5f, wheel);
      EXPECT_GE(z, kMinZoom) << fit << " " << wheel;
      EXPECT_LE(z, kMaxZoom) << fit << " " << wheel;
    }
  DisplaySettings d;
  d.fit = false;
  d.zoom = 2.f;
  EXPECT_FLOAT_EQ(zoomAfterWheel(d, 7.f, 1.f), 2.5f);  // from the display's zoom
  d.fit = true;
  EXPECT_FLOAT_EQ(zoomAfterWheel(d, 4.f, -1.f), 3.2f);  // from what is on screen
}

TEST(ImageLayout, AFittedZoomBelowTheRangeIsNotForcedUpByZoomingOut) {
  DisplaySettings d;
  d.fit = true;
  EXPECT_FLOAT_EQ(zoomAfterWheel(d, 0.01f, -3.f), 0.01f);
  EXPECT_NEAR(zoomAfterWheel(d, 0.01f, 1.f), 0.0125f, 1e-7f);
}

TEST(ImageLayout, LayoutZoomIsPositiveAndFinite) {
  DisplaySettings d;
  d.fit = false;
  for (float z : {0.f, -1.f, kNaN, kInf}) {
    d.zoom = z;
    ImageLayout l = layoutImage(d, 320, 240, 0, 800, 600);
    EXPECT_EQ(l.zoom, 1.f) << z;
  }
  d.fit = true;
  ImageLayout l = layoutImage(d, 320, 240, 0, 0, 0);
  EXPECT_EQ(l.zoom, 1.f);
}

}  // namespace
}  // namespace penumbra::ui
