#include "core/sampling/chi2.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>
#include <utility>

namespace penumbra {
namespace {

Chi2Options quick(uint64_t seed = 1) {
  Chi2Options o;
  o.sampleCount = 300000;
  o.resolution = 31;
  o.seed = seed;
  return o;
}

TEST(Chi2, SidakCorrection) {
  EXPECT_DOUBLE_EQ(sidakAlpha(0.01, 1), 0.01);
  double a = sidakAlpha(0.01, 20);
  EXPECT_NEAR(1.0 - std::pow(1.0 - a, 20), 0.01, 1e-12);
  EXPECT_LT(a, 0.01 / 20 * 1.01);
}

TEST(Chi2, IntegratesKnownDensities) {
  // constant on the square: exact
  EXPECT_NEAR(integratePdf(
                  Chi2Domain::square(0, 1), [](const Vec3&) { return 1.0; }, 7),
              1.0, 1e-12);
  // indicator of the disk / pi: a curved jump through many cells
  double disk = integratePdf(Chi2Domain::square(-1, 1), warpPdfFunction(WarpType::UniformDisk, 0.f), 51);
  EXPECT_NEAR(disk, 1.0, 1e-6);
  // sphere measure dphi dw: constant 1/(4 pi) over the sphere, and the hemisphere's half in the outside cell
  EXPECT_NEAR(integratePdf(Chi2Domain::sphere(2.0), warpPdfFunction(WarpType::UniformSphere, 0.f), 11), 1.0,
              1e-7);  // kInv4Pi is a float
  Chi2Expected e = integrateCells(Chi2Domain::sphere(1.0), warpPdfFunction(WarpType::UniformSphere, 0.f), 11);
  EXPECT_NEAR(std::accumulate(e.cells.begin(), e.cells.end(), 0.0), 0.5, 1e-7);
  EXPECT_NEAR(e.outside, 0.5, 1e-7);
  EXPECT_EQ(e.resX, 22);
  EXPECT_EQ(e.resY, 11);
}

TEST(Chi2, AcceptsConsistentPairAndReportsGrids) {
  Chi2Options o = quick();
  Chi2Result r = chi2Test(chi2DomainFor(WarpType::CosineHemisphere, 0.f),
                          warpSampleFunction(WarpType::CosineHemisphere, 0.f),
                          warpPdfFunction(WarpType::CosineHemisphere, 0.f), o);
  EXPECT_TRUE(r.accepted) << r.message;
  EXPECT_EQ(r.resX, 62);
  EXPECT_EQ(r.resY, 31);
  ASSERT_EQ(r.observed.size(), size_t(62 * 31));
  ASSERT_EQ(r.expected.size(), r.observed.size());
  EXPECT_DOUBLE_EQ(std::accumulate(r.observed.begin(), r.observed.end(), 0.0) + r.observedOutside, 300000.0);
  EXPECT_NEAR(std::accumulate(r.expected.begin(), r.expected.end(), 0.0) + r.expectedOutside, 300000.0, 1.0);
  EXPECT_GT(r.dof, 1000);
  EXPECT_GT(r.pValue, 0.0);
}

// ---- the test of the test: inconsistent pairs must be rejected ----------------------------------
TEST(Chi2, RejectsCosineSamplesJudgedByUniformHemispherePdf) {
  for (uint64_t seed : {1u, 2u, 3u}) {
    Chi2Result r = chi2Test(chi2DomainFor(WarpType::UniformHemisphere, 0.f),
                            warpSampleFunction(WarpType::CosineHemisphere, 0.f),
                            warpPdfFunction(WarpType::UniformHemisphere, 0.f), quick(seed));
    EXPECT_FALSE(r.accepted);
    EXPECT_LT(r.pValue, 1e-6);
  }
}

TEST(Chi2, RejectsUniformSpherePdfTimesTwo) {
  Chi2Result r =
      chi2Test(chi2DomainFor(WarpType::UniformSphere, 0.f), warpSampleFunction(WarpType::UniformSphere, 0.f),
               warpPdfFunction(WarpType::UniformSphere, 0.f, 2.0), quick());
  EXPECT_FALSE(r.accepted);
}

TEST(Chi2, RejectsTentJudgedByUniformSquare) {
  // on the uniform square's domain: tent samples outside [0,1]^2 land where the pdf integrates to 0
  Chi2Result r =
      chi2Test(chi2DomainFor(WarpType::UniformSquare, 0.f), warpSampleFunction(WarpType::Tent, 0.f),
               warpPdfFunction(WarpType::UniformSquare, 0.f), quick());
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.message.find("integrates to 0"), std::string::npos) << r.message;
  // on the tent's domain: uniform-square density where the tent has mass elsewhere
  r = chi2Test(chi2DomainFor(WarpType::Tent, 0.f), warpSampleFunction(WarpType::Tent, 0.f),
               warpPdfFunction(WarpType::UniformSquare, 0.f), quick());
  EXPECT_FALSE(r.accepted);
}

TEST(Chi2, RejectsSmallScaleErrorAndHemisphereSamplesOfASphere) {
  // a 5% error in normalisation is visible at this sample count
  Chi2Result r =
      chi2Test(chi2DomainFor(WarpType::UniformDisk, 0.f), warpSampleFunction(WarpType::UniformDisk, 0.f),
               warpPdfFunction(WarpType::UniformDisk, 0.f, 1.05), quick());
  EXPECT_FALSE(r.accepted);
  // sphere samples judged by the hemisphere pdf: samples below the horizon where it integrates to 0
  r = chi2Test(chi2DomainFor(WarpType::UniformHemisphere, 0.f),
               warpSampleFunction(WarpType::UniformSphere, 0.f),
               warpPdfFunction(WarpType::UniformHemisphere, 0.f), quick());
  EXPECT_FALSE(r.accepted);
  // a slightly wrong Beckmann roughness
  r = chi2Test(chi2DomainFor(WarpType::Beckmann, 0.2f), warpSampleFunction(WarpType::Beckmann, 0.2f),
               warpPdfFunction(WarpType::Beckmann, 0.21f), quick());
  EXPECT_FALSE(r.accepted);
}

TEST(Chi2, RejectsNaNSamples) {
  Chi2Result r = chi2Test(
      Chi2Domain::square(0, 1),
      [](Vec2 u) { return u.x < 0.001f ? Vec3(std::nanf(""), 0, 0) : Vec3(u, 0.f); },
      [](const Vec3&) { return 1.0; }, quick());
  EXPECT_FALSE(r.accepted);
  EXPECT_GT(r.invalidSamples, 0u);
}

TEST(Chi2, ZeroExpectedCellWithSamplesRejectsImmediately) {
  // pdf claims nothing in the left half, samples are uniform
  Chi2Result r = chi2Test(
      Chi2Domain::square(0, 1), [](Vec2 u) { return Vec3(u, 0.f); },
      [](const Vec3& v) { return v.x < 0.5f ? 0.0 : 2.0; }, quick());
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.message.find("integrates to 0"), std::string::npos) << r.message;
}

// ---- few samples on a fine grid -------------------------------------------------------------------

Chi2Options fewSamples(uint64_t n, int res) {
  Chi2Options o;
  o.sampleCount = n;
  o.resolution = res;
  return o;
}

TEST(Chi2, TooFewSamplesForTheGridIsInconclusiveNotRejected) {
  // 100 samples in 2000 x 1000 cells: every cell expects 5e-5 samples; pooled, one cell remains.
  Chi2Result r = chi2Test(chi2DomainFor(WarpType::CosineHemisphere, 0.f),
                          warpSampleFunction(WarpType::CosineHemisphere, 0.f),
                          warpPdfFunction(WarpType::CosineHemisphere, 0.f), fewSamples(100, 1000));
  EXPECT_TRUE(r.inconclusive);
  EXPECT_FALSE(r.accepted);
  EXPECT_STREQ(chi2Verdict(r), "inconclusive");
  EXPECT_EQ(r.dof, 0);
  EXPECT_TRUE(std::isnan(r.pValue));
  EXPECT_NE(r.message.find("too few samples"), std::string::npos) << r.message;
  // The expected counts still cover the whole grid (for plots) and sum to the samples.
  EXPECT_NEAR(std::accumulate(r.expected.begin(), r.expected.end(), 0.0) + r.expectedOutside, 100.0, 1e-3);
  EXPECT_GT(*std::min_element(r.expected.begin(), r.expected.end() - 2000), 0.0);  // all but the horizon row
}

TEST(Chi2, FewSamplesWherePdfIsZeroStillReject) {
  // Samples of the whole square judged by the disk's pdf: the corners' samples are impossible, which
  // rejects at any sample count, even when every cell can only be pooled.
  Chi2Result r = chi2Test(
      Chi2Domain::square(-1, 1), [](Vec2 u) { return Vec3(2.f * u.x - 1.f, 2.f * u.y - 1.f, 0.f); },
      warpPdfFunction(WarpType::UniformDisk, 0.f), fewSamples(100, 1000));
  EXPECT_FALSE(r.accepted);
  EXPECT_FALSE(r.inconclusive);
  EXPECT_NE(r.message.find("integrates to 0"), std::string::npos) << r.message;
}

TEST(Chi2, BlocksThatCanOnlyBePooledGiveTheSameVerdictAndStatistic) {
  // 3000 samples over 100 x 100 cells (0.3 expected each): the sparse blocks share their integral
  // instead of integrating each cell; the pooled statistic is that of integrating every cell.
  for (auto [type, param] : {std::pair{WarpType::Tent, 0.f}, std::pair{WarpType::Beckmann, 0.05f}}) {
    Chi2Options o = fewSamples(3000, 100);
    Chi2Result r = chi2Test(chi2DomainFor(type, param), warpSampleFunction(type, param),
                            warpPdfFunction(type, param), o);
    Chi2Expected exact = integrateCells(chi2DomainFor(type, param), warpPdfFunction(type, param), 100);
    double pooledExpected = 0.0;
    for (size_t c = 0; c < exact.cells.size(); ++c)
      if (3000 * exact.cells[c] < o.minExpected) pooledExpected += 3000 * exact.cells[c];
    double ours = 0.0;
    for (double e : r.expected)
      if (e < o.minExpected) ours += e;
    EXPECT_NEAR(ours, pooledExpected, 1e-6 * 3000) << warpTypeName(type);
    EXPECT_FALSE(r.inconclusive && r.accepted);
  }
}

TEST(Chi2, CancelStopsTheTest) {
  std::atomic<bool> cancel{true};
  Chi2Options o = fewSamples(1'000'000'000, 1000);
  o.cancel = &cancel;
  EXPECT_THROW(chi2Test(chi2DomainFor(WarpType::Tent, 0.f), warpSampleFunction(WarpType::Tent, 0.f),
                        warpPdfFunction(WarpType::Tent, 0.f), o),
               Cancelled);
}
}  // namespace
}  // namespace penumbra
