#include "core/scene/property.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/math/error.h"

namespace penumbra {
namespace {

Property make(const std::string& name, PropertyType type, const std::string& text, int line) {
  Property p;
  p.name = name;
  p.line = line;
  EXPECT_TRUE(parsePropertyValue(type, text, p)) << text;
  return p;
}

PropertyList sample() {
  PropertyList l;
  l.setContext("scene.xml", "integrator", "ao");
  l.add(make("nSamples", PropertyType::Integer, "4", 7));
  l.add(make("sampling", PropertyType::String, "cosine", 8));
  l.add(make("radius", PropertyType::Float, "0.5", 9));
  l.add(make("center", PropertyType::Point, "1, 2,3", 10));
  l.add(make("albedo", PropertyType::Color, "0.25", 11));
  l.add(make("shadows", PropertyType::Boolean, "false", 12));
  return l;
}

TEST(PropertyValues, IntegersAreStrict) {
  int64_t v;
  EXPECT_TRUE(parseIntegerValue("42", v));
  EXPECT_EQ(v, 42);
  EXPECT_TRUE(parseIntegerValue(" -7 ", v));
  EXPECT_EQ(v, -7);
  EXPECT_TRUE(parseIntegerValue("-0", v));
  EXPECT_EQ(v, 0);
  EXPECT_TRUE(parseIntegerValue("4294967296", v));  // fits int64; range checks are the builder's
  EXPECT_EQ(v, 4294967296LL);
  for (const char* bad : {"3.5", "1e3", "4abc", "", " ", "0x10", "++1", "9223372036854775808", "nan"})
    EXPECT_FALSE(parseIntegerValue(bad, v)) << bad;
}

TEST(PropertyValues, FloatsRejectNonFinite) {
  double v;
  EXPECT_TRUE(parseFloatValue("0.05", v));
  EXPECT_DOUBLE_EQ(v, 0.05);
  EXPECT_TRUE(parseFloatValue("1e3", v));
  EXPECT_EQ(v, 1000.0);
  EXPECT_TRUE(parseFloatValue("+.5", v));
  EXPECT_EQ(v, 0.5);
  EXPECT_TRUE(parseFloatValue("-0", v));
  EXPECT_EQ(v, 0.0);
  EXPECT_FALSE(std::signbit(v));
  EXPECT_TRUE(parseFloatValue("-0.0", v));
  EXPECT_FALSE(std::signbit(v));
  for (const char* bad : {"nan", "NaN", "inf", "-inf", "infinity", "1e999", "-1e999", "abc", "1.0f", "",
                          "1,5", "0x1p3", "1..2"})
    EXPECT_FALSE(parseFloatValue(bad, v)) << bad;
}

TEST(PropertyValues, Vectors) {
  Vec3 v;
  EXPECT_TRUE(parseVec3Value("1, 2, 3", v));
  EXPECT_EQ(v, Vec3(1, 2, 3));
  EXPECT_TRUE(parseVec3Value("1 2 3", v));
  EXPECT_EQ(v, Vec3(1, 2, 3));
  EXPECT_TRUE(parseVec3Value("0, -0.05,0", v));
  EXPECT_EQ(v, Vec3(0, -0.05f, 0));
  EXPECT_FALSE(std::signbit(v.x));
  EXPECT_TRUE(parseVec3Value("-0,0,0", v));
  EXPECT_FALSE(std::signbit(v.x));
  EXPECT_FALSE(parseVec3Value("1, 2", v));
  EXPECT_FALSE(parseVec3Value("1, 2, 3, 4", v));
  EXPECT_FALSE(parseVec3Value("1,,2,3", v));
  EXPECT_FALSE(parseVec3Value("1,2,3,", v));
  EXPECT_FALSE(parseVec3Value("1, nan, 3", v));
  EXPECT_FALSE(parseVec3Value("1, 1e39, 3", v));  // double but not float
  EXPECT_FALSE(parseVec3Value("0.5", v));
  EXPECT_TRUE(parseVec3Value("0.5", v, true));
  EXPECT_EQ(v, Vec3(0.5f));
}

TEST(PropertyList, GettersWithAliasesAndDefaults) {
  PropertyList l = sample();
  EXPECT_EQ(l.getInteger({"shadingSamples", "nSamples"}, 1), 4);
  EXPECT_EQ(l.getString({"sampler", "sampling", "warp-type"}, "uniform"), "cosine");
  EXPECT_FLOAT_EQ(l.getFloat({"radius"}, 1.f), 0.5f);
  EXPECT_FLOAT_EQ(l.getFloat({"nSamples"}, 1.f), 4.f);  // integer accepted as float
  EXPECT_EQ(l.getPoint({"center"}, Vec3(0)), Vec3(1, 2, 3));
  EXPECT_EQ(l.getColor({"albedo"}, Vec3(0)), Vec3(0.25f));
  EXPECT_FALSE(l.getBoolean({"shadows"}, true));
  EXPECT_EQ(l.getInteger({"missing"}, 17), 17);
  EXPECT_EQ(l.getTransform({"toWorld"}, glm::mat4(2.f)), glm::mat4(2.f));
  EXPECT_TRUE(l.has({"x", "radius"}));
  EXPECT_FALSE(l.has({"x"}));
  EXPECT_EQ(l.lineOf({"radius"}), 9);
  EXPECT_EQ(l.lineOf({"nope"}), 0);
  ASSERT_NE(l.find({"sampling"}), nullptr);
  EXPECT_EQ(l.find({"sampling"})->stringValue, "cosine");
  EXPECT_TRUE(l.unusedWarnings().empty());
}

TEST(PropertyList, TypeMismatchNamesFileAndLine) {
  PropertyList l = sample();
  try {
    l.getInteger({"radius"}, 0);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), "scene.xml");
    EXPECT_EQ(e.line(), 9);
    EXPECT_NE(std::string(e.what()).find("scene.xml:9:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("expected an integer"), std::string::npos) << e.what();
  }
  EXPECT_THROW(l.getFloat({"sampling"}, 0), Error);
  EXPECT_THROW(l.getString({"nSamples"}, ""), Error);
  EXPECT_THROW(l.getVector({"center"}, Vec3(0)), Error);  // a point is not a vector
  EXPECT_THROW(l.getBoolean({"nSamples"}, false), Error);
  try {
    l.getPoint({"albedo"}, Vec3(0));
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.line(), 11);
  }
}

TEST(PropertyList, DuplicateAndConflictingAliases) {
  PropertyList l = sample();
  try {
    l.add(make("radius", PropertyType::Float, "1", 20));
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.line(), 20);
    EXPECT_NE(std::string(e.what()).find("line 9"), std::string::npos) << e.what();
  }
  l.add(make("shadingSamples", PropertyType::Integer, "2", 21));
  EXPECT_THROW(l.getInteger({"shadingSamples", "nSamples"}, 1), Error);
}

TEST(PropertyList, FloatOutOfFloatRange) {
  PropertyList l;
  l.setContext("a.xml", "camera", "perspective");
  l.add(make("fov", PropertyType::Float, "1e300", 3));
  EXPECT_THROW(l.getFloat({"fov"}, 30.f), Error);
}

TEST(PropertyList, UnusedWarningsMentionLine) {
  PropertyList l = sample();
  l.getInteger({"nSamples"}, 1);
  l.getString({"sampling"}, "");
  l.getFloat({"radius"}, 0);
  l.getPoint({"center"}, Vec3(0));
  l.getColor({"albedo"}, Vec3(0));
  auto w = l.unusedWarnings();
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0], "scene.xml:12: warning: property \"shadows\" of <integrator type=\"ao\"> is not used");
}

TEST(PropertyList, SetKeepsExistingType) {
  PropertyList l = sample();
  l.set("nSamples", "64");
  EXPECT_EQ(l.getInteger({"nSamples"}, 1), 64);
  EXPECT_EQ(l.lineOf({"nSamples"}), 7);
  try {
    l.set("nSamples", "3.5");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.line(), 7);
    EXPECT_NE(std::string(e.what()).find("expected an integer"), std::string::npos) << e.what();
  }
  l.set("radius", "2");  // float property: "2" parses as a float
  EXPECT_EQ(l.find({"radius"})->type, PropertyType::Float);
  EXPECT_FLOAT_EQ(l.getFloat({"radius"}, 0), 2.f);
  EXPECT_THROW(l.set("radius", "nan"), Error);
  l.set("sampling", "uniform");
  EXPECT_EQ(l.getString({"sampling"}, ""), "uniform");
  l.set("center", "0 0 1");
  EXPECT_EQ(l.getPoint({"center"}, Vec3(0)), Vec3(0, 0, 1));
  EXPECT_THROW(l.set("shadows", "yes"), Error);
}

TEST(PropertyList, SetInfersTypeOfNewProperty) {
  PropertyList l;
  l.set("a", "true");
  l.set("b", "12");
  l.set("c", "-0");
  l.set("d", "0.25");
  l.set("e", "area");
  l.set("f", "1, 0.5, 0");
  EXPECT_EQ(l.find({"a"})->type, PropertyType::Boolean);
  EXPECT_EQ(l.find({"b"})->type, PropertyType::Integer);
  EXPECT_EQ(l.find({"c"})->type, PropertyType::Integer);
  EXPECT_EQ(l.find({"d"})->type, PropertyType::Float);
  EXPECT_EQ(l.find({"e"})->type, PropertyType::String);
  EXPECT_EQ(l.find({"f"})->type, PropertyType::String);
  EXPECT_EQ(l.lineOf({"b"}), 0);
  EXPECT_FLOAT_EQ(l.getFloat({"b"}, 0), 12.f);
  EXPECT_EQ(l.getColor({"f"}, Vec3(0)), Vec3(1, 0.5f, 0));  // override string read as color
  l.set("b", "x");                                          // an override property is re-inferred
  EXPECT_EQ(l.getString({"b"}, ""), "x");
}

}  // namespace
}  // namespace penumbra
