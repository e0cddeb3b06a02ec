#include "core/image/tonemap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace penumbra {
namespace {

TEST(Tonemap, KnownValues) {
  EXPECT_EQ(toSrgb8(0.f), 0);
  EXPECT_EQ(toSrgb8(1.f), 255);
  EXPECT_EQ(toSrgb8(-3.f), 0);
  EXPECT_EQ(toSrgb8(5.f), 255);
  EXPECT_EQ(toSrgb8(0.5f), 188);       // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 -> 187.5 -> 188
  EXPECT_EQ(toSrgb8(0.18f), 118);      // 0.4614 -> 117.66 -> 118
  EXPECT_EQ(toSrgb8(0.0031308f), 10);  // linear segment: 12.92 * 0.0031308 = 0.04045 -> 10.31 -> 10
  EXPECT_EQ(toSrgb8(0.001f), 3);       // 0.01292 * 255 = 3.29 -> 3
  EXPECT_EQ(toSrgb8(std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_EQ(toSrgb8(std::numeric_limits<float>::infinity()), 0);
  EXPECT_EQ(toSrgb8(-std::numeric_limits<float>::infinity()), 0);
}

TEST(Tonemap, OetfIsContinuousAndInvertible) {
  const float t = 0.0031308f;
  EXPECT_NEAR(srgbOetf(std::nextafter(t, 0.f)), srgbOetf(std::nextafter(t, 1.f)), 1e-6f);
  for (float v : {0.f, 0.002f, 0.01f, 0.2f, 0.5f, 0.9f, 1.f})
    EXPECT_NEAR(srgbToLinear(srgbOetf(v)), v, 1e-6f);
  // Every 8-bit code survives decode + encode.
  for (int k = 0; k < 256; ++k) EXPECT_EQ(toSrgb8(srgbToLinear(k / 255.f)), k) << k;
}

TEST(Tonemap, ExposureMultipliesByPowerOfTwo) {
  Image img(2, 1);
  img.set(0, 0, Color3(0.125f, 0.25f, 0.5f));
  img.set(1, 0, Color3(std::numeric_limits<float>::max(), std::numeric_limits<float>::quiet_NaN(), 0.f));
  auto b = toSrgb8(img, 1.f);
  EXPECT_EQ(b[0], toSrgb8(0.25f));
  EXPECT_EQ(b[1], toSrgb8(0.5f));
  EXPECT_EQ(b[2], toSrgb8(1.f));
  EXPECT_EQ(b[3], 255);  // finite pixel overflowing under exposure is white, not black
  EXPECT_EQ(b[4], 0);    // NaN -> 0
  auto d = toSrgb8(img, -2.f);
  EXPECT_EQ(d[2], toSrgb8(0.125f));
}

}  // namespace
}  // namespace penumbra
