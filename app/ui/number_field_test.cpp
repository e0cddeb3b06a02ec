// The viewer's numeric fields: whatever is typed, the value stays within the field's documented
// range and the note says what was done (3000000000 in sampleCount is 16777216, not 1).
#include "app/ui/number_field.h"

#include <gtest/gtest.h>

#include <string>

#include "core/math/error.h"
#include "core/scene/scene_builder.h"

using namespace penumbra;
using namespace penumbra::ui;

namespace {

double valueOf(const NumberEntry& e) {
  EXPECT_TRUE(e.value.has_value()) << e.note;
  return e.value.value_or(-1);
}

}  // namespace

TEST(NumberField, NumbersTooLargeForAnIntClampToTheLargestValue) {
  NumberEntry e = parseNumberEntry("3000000000", fields::kSampleCount, 64);
  EXPECT_EQ(valueOf(e), 16777216.0);
  EXPECT_EQ(e.note, "clamped to 16777216 (the largest sampleCount)");
  e = parseNumberEntry("3000000000", shadingSamplesField("nSamples"), 4);
  EXPECT_EQ(valueOf(e), 65536.0);
  EXPECT_EQ(e.note, "clamped to 65536 (the largest nSamples)");
  e = parseNumberEntry("99999999999999999999999", fields::kTargetSpp, 64);
  EXPECT_EQ(valueOf(e), double(1 << 30));
  EXPECT_EQ(e.note, "clamped to 1073741824 (the largest target spp)");
  e = parseNumberEntry("1e400", fields::kSeed, 0);  // beyond double: still the largest seed
  EXPECT_EQ(valueOf(e), 9007199254740992.0);
}

TEST(NumberField, NegativeAndZeroClampToTheSmallest) {
  NumberEntry e = parseNumberEntry("-5", fields::kSampleCount, 64);
  EXPECT_EQ(valueOf(e), 1.0);
  EXPECT_EQ(e.note, "clamped to 1 (the smallest sampleCount)");
  e = parseNumberEntry("0", shadingSamplesField("lightSamples"), 4);
  EXPECT_EQ(valueOf(e), 1.0);
  EXPECT_EQ(e.note, "clamped to 1 (the smallest lightSamples)");
  e = parseNumberEntry("-1", fields::kSeed, 7);
  EXPECT_EQ(valueOf(e), 0.0);
  e = parseNumberEntry("0", fields::kTargetSpp, 64);  // 0 is "never stop": in range
  EXPECT_EQ(valueOf(e), 0.0);
  EXPECT_EQ(e.note, "");
}

TEST(NumberField, SecondsAreCappedAtOneWeek) {
  NumberEntry e = parseNumberEntry("1e30", fields::kSeconds, 10);
  EXPECT_EQ(valueOf(e), 604800.0);
  EXPECT_EQ(e.note, "clamped to 604800.0 s (the largest time budget)");
  e = parseNumberEntry("0", fields::kSeconds, 10);
  EXPECT_EQ(valueOf(e), 0.1);
  EXPECT_EQ(e.note, "clamped to 0.1 s (the smallest time budget)");
  e = parseNumberEntry(" 2.5 ", fields::kSeconds, 10);
  EXPECT_EQ(valueOf(e), 2.5);
  EXPECT_EQ(e.note, "");
}

TEST(NumberField, FractionsOfCountsRoundAndSayWhy) {
  NumberEntry e = parseNumberEntry("2.6", fields::kSampleCount, 64);
  EXPECT_EQ(valueOf(e), 3.0);
  EXPECT_EQ(e.note, "rounded to 3 (sampleCount is a whole number)");
  e = parseNumberEntry("1e3", fields::kSampleCount, 64);
  EXPECT_EQ(valueOf(e), 1000.0);
  EXPECT_EQ(e.note, "");
}

TEST(NumberField, TextThatIsNoNumberKeepsTheValue) {
  for (const char* text : {"", "abc", "12abc", "nan", "--3", "1e"}) {
    NumberEntry e = parseNumberEntry(text, fields::kSampleCount, 64);
    EXPECT_FALSE(e.value.has_value()) << text;
    EXPECT_EQ(e.note, "\"" + std::string(text) + "\" is not a number: kept 64") << text;
  }
}

TEST(NumberField, SliderValuesClampLikeTypedOnes) {
  NumberEntry e = clampNumber(1e30, fields::kExposure, 0);
  EXPECT_EQ(valueOf(e), 20.0);
  EXPECT_EQ(e.note, "clamped to 20.00 stops (the largest exposure)");
  e = clampNumber(500, fields::kFov, 40);
  EXPECT_EQ(valueOf(e), 179.0);
  e = clampNumber(-7, fields::kZoomStops, 0);
  EXPECT_EQ(valueOf(e), -4.0);
  e = clampNumber(150, fields::kDividerPercent, 50);
  EXPECT_EQ(valueOf(e), 100.0);
  e = clampNumber(std::nan(""), fields::kFov, 40);
  EXPECT_FALSE(e.value.has_value());
  EXPECT_EQ(e.note, "not a number: kept 40.0 deg");
}

// The fields' ranges are the scene file's: the largest value loads, one more does not.
TEST(NumberField, RangesAreTheSceneFilesRanges) {
  auto loads = [](const std::string& key, double v) {
    try {
      loadSceneFromString(defaultSceneXml(), "default", ".", {{key, formatNumber(v, fields::kSampleCount)}});
      return true;
    } catch (const Error&) {
      return false;
    }
  };
  EXPECT_TRUE(loads("sampler.sampleCount", fields::kSampleCount.max));
  EXPECT_FALSE(loads("sampler.sampleCount", fields::kSampleCount.max + 1));
  EXPECT_TRUE(loads("sampler.sampleCount", fields::kSampleCount.min));
  EXPECT_FALSE(loads("sampler.sampleCount", fields::kSampleCount.min - 1));
  EXPECT_TRUE(loads("integrator.nSamples", fields::kShadingSamples.max));
  EXPECT_FALSE(loads("integrator.nSamples", fields::kShadingSamples.max + 1));
}
