#include "core/sampling/chi2.h"

#include <gtest/gtest.h>

#include <numeric>

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

}  // namespace
}  // namespace penumbra
