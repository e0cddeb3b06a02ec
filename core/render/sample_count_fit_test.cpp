#include "core/render/sample_count_fit.h"

#include <gtest/gtest.h>

namespace penumbra {
namespace {

RenderSettings withSampler(SamplerKind k, uint32_t sceneCount) {
  RenderSettings s;
  s.samplerKind = k;
  s.sampleCount = sceneCount;
  return s;
}

TEST(SampleCountFit, AKnownTargetSetsTheStrata) {
  RenderSettings s = withSampler(SamplerKind::Stratified, 4);
  EXPECT_EQ(fitSampleCountToTarget(s, 64), "");
  EXPECT_EQ(s.sampleCount, 64u);
  RenderSettings z = withSampler(SamplerKind::ZSobol, 4);
  EXPECT_EQ(fitSampleCountToTarget(z, 16), "");
  EXPECT_EQ(z.sampleCount, 16u);
}

TEST(SampleCountFit, SaysWithNumbersWhatItCannotStratify) {
  RenderSettings s = withSampler(SamplerKind::Stratified, 4);
  std::string m = fitSampleCountToTarget(s, 50);
  EXPECT_EQ(s.sampleCount, 50u);
  EXPECT_NE(m.find("50 spp is not a square"), std::string::npos) << m;
  EXPECT_NE(m.find("7x7 = 49"), std::string::npos) << m;
  RenderSettings z = withSampler(SamplerKind::ZSobol, 4);
  m = fitSampleCountToTarget(z, 50);
  EXPECT_NE(m.find("share nets at 64 samples"), std::string::npos) << m;
}

TEST(SampleCountFit, AnUnknownTargetKeepsTheScenesCountAndSaysWhatFollows) {
  RenderSettings s = withSampler(SamplerKind::Stratified, 16);
  std::string m = fitSampleCountToTarget(s, 0);
  EXPECT_EQ(s.sampleCount, 16u);
  EXPECT_NE(m.find("2-D: 4x4"), std::string::npos) << m;
  EXPECT_NE(m.find("fresh jitter"), std::string::npos) << m;
  RenderSettings z = withSampler(SamplerKind::ZSobol, 16);
  EXPECT_NE(fitSampleCountToTarget(z, 0).find("share nets at sampleCount 16"), std::string::npos);
}

TEST(SampleCountFit, OtherSamplersAreLeftAlone) {
  for (SamplerKind k : {SamplerKind::Independent, SamplerKind::Sobol}) {
    RenderSettings s = withSampler(k, 4);
    EXPECT_EQ(fitSampleCountToTarget(s, 64), "");
    EXPECT_EQ(fitSampleCountToTarget(s, 0), "");
    EXPECT_EQ(s.sampleCount, 4u);
  }
}

}  // namespace
}  // namespace penumbra
