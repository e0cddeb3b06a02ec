#include "core/sampling/sampler_table.h"

#include <gtest/gtest.h>

#include <set>

namespace penumbra {
namespace {

TEST(SamplerTable, RowsAreIndexedByKind) {
  ASSERT_EQ(samplerTable().size(), size_t(kSamplerKindCount));
  for (size_t i = 0; i < samplerTable().size(); ++i) EXPECT_EQ(size_t(samplerTable()[i].kind), i);
}

TEST(SamplerTable, EverySpellingParsesToItsRow) {
  for (const SamplerRow& r : samplerTable())
    for (std::string_view name : r.name.list()) {
      SamplerKind k;
      ASSERT_TRUE(parseSamplerKind(std::string(name), k)) << name;
      EXPECT_EQ(k, r.kind) << name;
    }
}

TEST(SamplerTable, CanonicalNamesRoundTrip) {
  for (const SamplerRow& r : samplerTable()) {
    SamplerKind k;
    ASSERT_TRUE(parseSamplerKind(samplerKindName(r.kind), k));
    EXPECT_EQ(k, r.kind);
  }
  EXPECT_STREQ(samplerKindName(SamplerKind::Stratified), "stratified");
}

TEST(SamplerTable, NamesAndLabelsAreUniqueAndDescribed) {
  std::set<std::string_view> names, labels;
  for (const SamplerRow& r : samplerTable()) {
    EXPECT_TRUE(labels.insert(r.label).second) << r.label;
    EXPECT_FALSE(r.description.empty()) << r.label;
    for (std::string_view n : r.name.list()) EXPECT_TRUE(names.insert(n).second) << n;
  }
}

TEST(SamplerTable, UnknownNameFailsAndTheMessageListsEveryRow) {
  SamplerKind k;
  EXPECT_FALSE(parseSamplerKind("halton", k));
  EXPECT_EQ(findSampler(""), nullptr);
  std::string accepted = acceptedSamplerNames();
  for (const SamplerRow& r : samplerTable())
    EXPECT_NE(accepted.find(std::string(r.name.canonical())), std::string::npos) << accepted;
}

TEST(SamplerTable, StratifiedAndZSobolShapeTheirPatternBySampleCount) {
  EXPECT_FALSE(samplerRow(SamplerKind::Independent).usesSampleCount());
  EXPECT_TRUE(samplerRow(SamplerKind::Stratified).usesSampleCount());
  EXPECT_FALSE(samplerRow(SamplerKind::Sobol).usesSampleCount());
  EXPECT_TRUE(samplerRow(SamplerKind::ZSobol).usesSampleCount());
}

// The rule of a row: its fit for a scene's sampleCount and a run's final count (0: not known).
SampleCountFit fit(SamplerKind kind, uint32_t sceneCount, uint32_t targetSpp) {
  const SampleCountRule rule = samplerRow(kind).fitSampleCount;
  if (!rule) ADD_FAILURE() << samplerKindName(kind) << " has no rule";
  return rule ? rule(sceneCount, targetSpp) : SampleCountFit{};
}

TEST(SamplerTable, IndependentAndSobolHaveNoRule) {
  EXPECT_EQ(samplerRow(SamplerKind::Independent).fitSampleCount, nullptr);
  EXPECT_EQ(samplerRow(SamplerKind::Sobol).fitSampleCount, nullptr);
}

TEST(SamplerTable, StratifiedTakesASquareTargetAsItsStrataSilently) {
  for (uint32_t spp : {1u, 4u, 49u, 64u, 65536u}) {
    SampleCountFit f = fit(SamplerKind::Stratified, 4, spp);
    EXPECT_EQ(f.sampleCount, spp);
    EXPECT_EQ(f.note, "") << spp;
  }
}

TEST(SamplerTable, StratifiedSaysWhatANonSquareTargetLeavesOut) {
  SampleCountFit f = fit(SamplerKind::Stratified, 4, 50);
  EXPECT_EQ(f.sampleCount, 50u);
  EXPECT_EQ(f.note,
            "stratified: 50 spp is not a square: 1-D dimensions use 50 strata, 2-D pairs 7x7 = 49; their "
            "remaining 1 samples per pixel repeat the strata with fresh jitter");
  f = fit(SamplerKind::Stratified, 64, 2);
  EXPECT_EQ(f.sampleCount, 2u);
  EXPECT_EQ(f.note,
            "stratified: 2 spp is not a square: 1-D dimensions use 2 strata, 2-D pairs 1x1 = 1; their "
            "remaining 1 samples per pixel repeat the strata with fresh jitter");
}

TEST(SamplerTable, StratifiedWithoutAFinalCountKeepsTheScenesAndSaysWhatFollows) {
  SampleCountFit f = fit(SamplerKind::Stratified, 16, 0);
  EXPECT_EQ(f.sampleCount, 16u);
  EXPECT_EQ(f.note,
            "stratified: the final sample count is not known (time limit or endless accumulation), so the "
            "strata are those of sampleCount 16 (1-D: 16, 2-D: 4x4); every further 16 samples repeat them "
            "with fresh jitter, and beyond them the error falls like independent sampling's");
  f = fit(SamplerKind::Stratified, 10, 0);  // not a square either: the grid is the largest square in it
  EXPECT_EQ(f.sampleCount, 10u);
  EXPECT_NE(f.note.find("(1-D: 10, 2-D: 3x3)"), std::string::npos) << f.note;
}

TEST(SamplerTable, ZSobolTakesAPowerOfTwoTargetAsItsSharedNetsSilently) {
  for (uint32_t spp : {1u, 2u, 16u, 1024u}) {
    SampleCountFit f = fit(SamplerKind::ZSobol, 4, spp);
    EXPECT_EQ(f.sampleCount, spp);
    EXPECT_EQ(f.note, "") << spp;
  }
}

TEST(SamplerTable, ZSobolSaysWhereANonPowerOfTwoTargetSharesItsNets) {
  SampleCountFit f = fit(SamplerKind::ZSobol, 4, 50);
  EXPECT_EQ(f.sampleCount, 50u);
  EXPECT_EQ(f.note,
            "zsobol: 50 spp is not a power of two: neighbouring pixels share nets at 64 samples, so at 50 "
            "their errors cancel only partly (each pixel's own power-of-two prefixes are still nets)");
}

TEST(SamplerTable, ZSobolWithoutAFinalCountKeepsTheScenesAndSaysWhereNetsAreShared) {
  SampleCountFit f = fit(SamplerKind::ZSobol, 16, 0);
  EXPECT_EQ(f.sampleCount, 16u);
  EXPECT_EQ(f.note,
            "zsobol: the final sample count is not known (time limit or endless accumulation): neighbouring "
            "pixels share nets at sampleCount 16 samples; before and after it each pixel's power-of-two "
            "prefixes are nets of their own");
  f = fit(SamplerKind::ZSobol, 24, 0);
  EXPECT_EQ(f.sampleCount, 24u);
  EXPECT_NE(f.note.find("share nets at sampleCount 24 rounded up to 32 samples;"), std::string::npos)
      << f.note;
}

// A scene's sampleCount of 0 is kept as it is; the note speaks of the one sample the sampler uses.
TEST(SamplerTable, ASceneCountOfZeroIsKeptAndDescribedAsOne) {
  for (SamplerKind kind : {SamplerKind::Stratified, SamplerKind::ZSobol}) {
    SampleCountFit f = fit(kind, 0, 0);
    EXPECT_EQ(f.sampleCount, 0u);
    EXPECT_NE(f.note.find("sampleCount 1"), std::string::npos) << f.note;
  }
}

}  // namespace
}  // namespace penumbra
