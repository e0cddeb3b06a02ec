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
  EXPECT_FALSE(samplerRow(SamplerKind::Independent).usesSampleCount);
  EXPECT_TRUE(samplerRow(SamplerKind::Stratified).usesSampleCount);
  EXPECT_FALSE(samplerRow(SamplerKind::Sobol).usesSampleCount);
  EXPECT_TRUE(samplerRow(SamplerKind::ZSobol).usesSampleCount);
}

}  // namespace
}  // namespace penumbra
