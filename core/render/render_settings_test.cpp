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
  auto ao = described(withSamples(aoBy(HemisphereWarp::Uniform), 4));
  EXPECT_EQ(ao["integrator"], "ao");
  EXPECT_EQ(ao["shadingSamples"], "4");
  EXPECT_EQ(ao["warp-type"], "uniform-hemisphere");
  EXPECT_EQ(ao.count("sampling"), 0u);
  auto hemi = described(withSamples(directByHemisphere(HemisphereWarp::Cosine), 2));
  EXPECT_EQ(hemi["integrator"], "direct");
  EXPECT_EQ(hemi["nSamples"], "2");
  EXPECT_EQ(hemi["measure"], "hemisphere");
  EXPECT_EQ(hemi["warp-type"], "cosine-hemisphere");
  auto area = described(withSamples(directByLight(LightMeasure::Area), 1));
  EXPECT_EQ(area["measure"], "area");
  EXPECT_EQ(area.count("warp-type"), 0u);
  auto psaBvh =
      described(withSamples(directByLight(LightMeasure::ProjectedSolidAngle, LightSelection::Bvh), 3));
  EXPECT_EQ(psaBvh["measure"], "projected-solid-angle");
  EXPECT_EQ(psaBvh["lightSelection"], "bvh");
  EXPECT_EQ(psaBvh["nSamples"], "3");
  IntegratorDesc misArea = withSamples(directByMis(LightMeasure::Area, MisHeuristic::Balance), 1);
  misArea.lightSamples = 3;
  misArea.bsdfSamples = 2;
  auto mis = described(misArea);
  EXPECT_EQ(mis["measure"], "mis");
  EXPECT_EQ(mis["lightMeasure"], "area");
  EXPECT_EQ(mis["heuristic"], "balance");
  EXPECT_EQ(mis["lightSamples"], "3");
  EXPECT_EQ(mis["bsdfSamples"], "2");
  EXPECT_EQ(mis.count("lightSelection"), 0u);  // MIS samples every light
  auto normals = described(withSamples(integratorOfType(IntegratorType::Normals), 1));
  EXPECT_EQ(normals["integrator"], "normals");
  EXPECT_EQ(normals.count("nSamples") + normals.count("shadingSamples"), 0u);
  EXPECT_EQ(normals["sampler"], "independent");
}

}  // namespace
}  // namespace penumbra
