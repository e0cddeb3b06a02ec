#include "core/render/render_settings.h"

#include <gtest/gtest.h>

#include <map>

namespace penumbra {
namespace {

std::map<std::string, std::string> described(const IntegratorDesc& d) {
  RenderSettings s;
  s.integrator = d;
  auto list = describeSettings(s);
  return {list.begin(), list.end()};
}

// Image metadata spells the integrator as a scene file would, in the canonical spelling.
TEST(DescribeSettings, WritesTheCanonicalSpellingOfTheStrategy) {
  auto ao = described({Strategy::AoUniform, 4});
  EXPECT_EQ(ao["integrator"], "ao");
  EXPECT_EQ(ao["shadingSamples"], "4");
  EXPECT_EQ(ao["warp-type"], "uniform-hemisphere");
  EXPECT_EQ(ao.count("sampling"), 0u);
  auto hemi = described({Strategy::DirectCosineHemisphere, 2});
  EXPECT_EQ(hemi["integrator"], "direct");
  EXPECT_EQ(hemi["nSamples"], "2");
  EXPECT_EQ(hemi["measure"], "hemisphere");
  EXPECT_EQ(hemi["warp-type"], "cosine-hemisphere");
  auto area = described({Strategy::DirectArea, 1});
  EXPECT_EQ(area["measure"], "area");
  EXPECT_EQ(area.count("warp-type"), 0u);
  auto normals = described({Strategy::Normals, 1});
  EXPECT_EQ(normals["integrator"], "normals");
  EXPECT_EQ(normals.count("nSamples") + normals.count("shadingSamples"), 0u);
  EXPECT_EQ(normals["sampler"], "independent");
}

}  // namespace
}  // namespace penumbra
