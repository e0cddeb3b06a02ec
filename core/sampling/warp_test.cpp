#include "core/sampling/warp.h"

#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "core/sampling/chi2.h"
#include "core/sampling/rng.h"

namespace penumbra {
namespace {

struct WarpCase {
  WarpType type;
  float param;
};

void PrintTo(const WarpCase& c, std::ostream* os) {
  *os << warpTypeName(c.type) << " param " << c.param;
}

std::string caseName(const testing::TestParamInfo<WarpCase>& info) {
  std::string s = warpTypeName(info.param.type);
  if (warpHasParameter(info.param.type)) s += "_" + std::to_string(info.index);
  for (char& c : s)
    if (c == '-') c = '_';
  return s;
}

std::vector<WarpCase> allCases() {
  std::vector<WarpCase> cases;
  for (int i = 0; i < kWarpTypeCount; ++i)
    if (!warpHasParameter(WarpType(i))) cases.push_back({WarpType(i), 0.f});
  for (float c :
       {-1.f, -0.5f, 0.f, 0.5f, 0.9f, 0.999f, float(std::sqrt(1.0 - 1e-4)), float(std::sqrt(1.0 - 1e-6))})
    cases.push_back({WarpType::UniformCone, c});
  for (float a : {0.05f, 0.2f, 0.5f, 1.0f}) cases.push_back({WarpType::Beckmann, a});
  return cases;
}

const float kExtremes[3] = {0.f, 0.5f, kOneMinusEpsilon};

Vec2 inverse(WarpType t, const Vec3& v, float param) {
  Vec2 p(v.x, v.y);
  switch (t) {
    case WarpType::UniformSquare:
      return p;
    case WarpType::Tent:
      return Warp::tentToSquare(p);
    case WarpType::UniformDisk:
      return Warp::uniformDiskToSquare(p);
    case WarpType::ConcentricDisk:
      return Warp::concentricDiskToSquare(p);
    case WarpType::UniformSphere:
      return Warp::uniformSphereToSquare(v);
    case WarpType::UniformHemisphere:
      return Warp::uniformHemisphereToSquare(v);
    case WarpType::CosineHemisphere:
      return Warp::cosineHemisphereToSquare(v);
    case WarpType::UniformCone:
      return Warp::uniformConeToSquare(v, param);
    case WarpType::Beckmann:
      return Warp::beckmannToSquare(v, param);
  }
  return p;
}

// Checks that v lies in the support of the warp (with float slack) and has a finite positive pdf.
void expectInDomain(const WarpCase& c, const Vec3& v) {
  ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
  switch (c.type) {
    case WarpType::UniformSquare:
      EXPECT_TRUE(v.x >= 0.f && v.x < 1.f && v.y >= 0.f && v.y < 1.f);
      break;
    case WarpType::Tent:
      EXPECT_TRUE(std::fabs(v.x) < 1.f && std::fabs(v.y) < 1.f);
      break;
    case WarpType::UniformDisk:
    case WarpType::ConcentricDisk:
      EXPECT_LE(v.x * v.x + v.y * v.y, 1.f + 1e-6f);
      break;
    default: {
      double len = std::sqrt(double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z);
      EXPECT_NEAR(len, 1.0, 1e-6);
      if (c.type == WarpType::UniformHemisphere || c.type == WarpType::CosineHemisphere ||
          c.type == WarpType::Beckmann) {
        EXPECT_GE(v.z, 0.f);
      }
      if (c.type == WarpType::UniformCone) {
        double r2 = double(v.x) * v.x + double(v.y) * v.y;
        double w = v.z > 0 ? r2 / (1.0 + v.z) : 1.0 - v.z;
        EXPECT_LE(w, double(1.f - c.param) * (1 + 1e-5));
      }
    }
  }
  if (!warpIsSpherical(c.type)) {
    EXPECT_EQ(v.z, 0.f);
  }
  float p = Warp::pdf(c.type, v, c.param);
  EXPECT_TRUE(std::isfinite(p));
  EXPECT_GT(p, 0.f) << "at " << v.x << " " << v.y << " " << v.z;
}

class WarpCaseTest : public testing::TestWithParam<WarpCase> {};

TEST_P(WarpCaseTest, SamplesLandInDomainWithPositivePdf) {
  const WarpCase c = GetParam();
  Rng rng(3, 4);
  for (int i = 0; i < 20000; ++i) {
    float u1 = rng.nextFloat();
    Vec2 u(u1, rng.nextFloat());
    expectInDomain(c, Warp::warp(c.type, u, c.param));
  }
}

TEST_P(WarpCaseTest, ExtremeInputsGiveFiniteInDomainSamples) {
  const WarpCase c = GetParam();
  for (float a : kExtremes)
    for (float b : kExtremes) {
      SCOPED_TRACE(testing::Message() << "u = (" << a << ", " << b << ")");
      expectInDomain(c, Warp::warp(c.type, Vec2(a, b), c.param));
    }
}

TEST_P(WarpCaseTest, InverseUndoesWarp) {
  const WarpCase c = GetParam();
  Rng rng(8, 1);
  for (int i = 0; i < 20000; ++i) {
    float u1 = rng.nextFloat();
    Vec2 u(u1, rng.nextFloat());
    Vec3 v = Warp::warp(c.type, u, c.param);
    if (c.type == WarpType::Beckmann && u.x > 0.999f)
      continue;  // 1 - u1 below float resolution of the inverse
    Vec2 back = inverse(c.type, v, c.param);
    double du = std::fabs(back.x - u.x);
    double dv = std::fabs(back.y - u.y);
    dv = std::min(dv, 1.0 - dv);  // azimuth wraps
    ASSERT_LT(du, 2e-4) << "u = " << u.x << " " << u.y << " back " << back.x << " " << back.y;
    ASSERT_LT(dv, 2e-4) << "u = " << u.x << " " << u.y << " back " << back.x << " " << back.y;
  }
}

TEST_P(WarpCaseTest, PdfIntegratesToOne) {
  const WarpCase c = GetParam();
  double total = integratePdf(chi2DomainFor(c.type, c.param), warpPdfFunction(c.type, c.param), 24);
  EXPECT_NEAR(total, 1.0, 1e-3);
}

// Every case x 3 seeds at alpha = 0.01 for the whole suite (Sidak-corrected per test).
TEST_P(WarpCaseTest, ChiSquarePassesForThreeSeeds) {
  const WarpCase c = GetParam();
  for (uint64_t seed : {1u, 2u, 3u}) {
    Chi2Options opt;
    opt.seed = seed;
    opt.sampleCount = 500000;
    opt.resolution = 41;
    opt.testCount = 3 * int(allCases().size()) + 6;
    Chi2Result r = chi2Test(chi2DomainFor(c.type, c.param), warpSampleFunction(c.type, c.param),
                            warpPdfFunction(c.type, c.param), opt);
    EXPECT_TRUE(r.accepted) << warpTypeName(c.type) << " param " << c.param << " seed " << seed << ": chi2 "
                            << r.chi2 << " dof " << r.dof << " p " << r.pValue << " " << r.message;
  }
}

INSTANTIATE_TEST_SUITE_P(AllWarps, WarpCaseTest, testing::ValuesIn(allCases()), caseName);

TEST(Warp, NamesRoundTripAndFlags) {
  for (int i = 0; i < kWarpTypeCount; ++i) {
    WarpType t;
    ASSERT_TRUE(parseWarpType(warpTypeName(WarpType(i)), t));
    EXPECT_EQ(int(t), i);
  }
  WarpType t;
  EXPECT_FALSE(parseWarpType("cosine", t));
  EXPECT_STREQ(warpTypeName(WarpType::CosineHemisphere), "cosine-hemisphere");
  EXPECT_TRUE(warpIsSpherical(WarpType::Beckmann));
  EXPECT_FALSE(warpIsSpherical(WarpType::ConcentricDisk));
  EXPECT_TRUE(warpHasParameter(WarpType::UniformCone));
  EXPECT_FALSE(warpHasParameter(WarpType::UniformSphere));
}

TEST(Warp, PdfIsExactlyZeroOutsideSupport) {
  const Vec3 below(0.6f, 0.f, -0.8f), south(0.f, 0.f, -1.f);
  for (WarpType t : {WarpType::UniformHemisphere, WarpType::CosineHemisphere}) {
    EXPECT_EQ(Warp::pdf(t, below), 0.f);
    EXPECT_EQ(Warp::pdf(t, south), 0.f);
  }
  EXPECT_EQ(Warp::squareToBeckmannPdf(below, 0.3f), 0.f);
  EXPECT_EQ(Warp::squareToBeckmannPdf(Vec3(1.f, 0.f, 0.f), 0.3f), 0.f);  // grazing: no 0/0
  EXPECT_EQ(Warp::squareToUniformSquarePdf(Vec2(-0.1f, 0.5f)), 0.f);
  EXPECT_EQ(Warp::squareToUniformSquarePdf(Vec2(0.5f, 1.1f)), 0.f);
  EXPECT_EQ(Warp::squareToTentPdf(Vec2(1.5f, 0.f)), 0.f);
  EXPECT_EQ(Warp::squareToTentPdf(Vec2(0.5f, -1.2f)), 0.f);
  EXPECT_EQ(Warp::squareToUniformDiskPdf(Vec2(0.8f, 0.7f)), 0.f);
  EXPECT_EQ(Warp::squareToConcentricDiskPdf(Vec2(-0.72f, 0.72f)), 0.f);
  // cone of cos(theta_max) = 0.5: a direction at cos 0.4 is outside
  EXPECT_EQ(Warp::squareToUniformConePdf(Vec3(std::sqrt(1.f - 0.16f), 0.f, 0.4f), 0.5f), 0.f);
  EXPECT_EQ(Warp::squareToUniformConePdf(below, 0.f), 0.f);
  EXPECT_EQ(Warp::squareToUniformConePdf(south, -0.5f), 0.f);
  // narrow cone, sin^2 = 1e-6: a direction with sin^2 = 2e-6 is outside, sin^2 = 0.5e-6 inside
  auto dir = [](double s2) { return Vec3(float(std::sqrt(s2)), 0.f, float(std::sqrt(1 - s2))); };
  EXPECT_EQ(Warp::squareToUniformConeSin2Pdf(dir(2e-6), 1e-6f), 0.f);
  EXPECT_GT(Warp::squareToUniformConeSin2Pdf(dir(0.5e-6), 1e-6f), 0.f);
  // degenerate parameters give 0, never inf or NaN
  EXPECT_EQ(Warp::squareToUniformConePdf(Vec3(0, 0, 1), 1.f), 0.f);
  EXPECT_EQ(Warp::squareToUniformConeSin2Pdf(Vec3(0, 0, 1), 0.f), 0.f);
  EXPECT_EQ(Warp::squareToBeckmannPdf(Vec3(0, 0, 1), 0.f), 0.f);
  // values inside
  EXPECT_FLOAT_EQ(Warp::squareToUniformSpherePdf(south), kInv4Pi);
  EXPECT_FLOAT_EQ(Warp::squareToCosineHemispherePdf(Vec3(0, 0, 1)), kInvPi);
  EXPECT_FLOAT_EQ(Warp::squareToTentPdf(Vec2(0.f, 0.5f)), 0.5f);
}

TEST(Warp, ConcentricDiskCentreAndCorners) {
  Vec2 centre = Warp::squareToConcentricDisk(Vec2(0.5f, 0.5f));
  EXPECT_LT(std::hypot(centre.x, centre.y), 1e-6f);
  for (float a : {0.f, kOneMinusEpsilon})
    for (float b : {0.f, kOneMinusEpsilon}) {
      Vec2 p = Warp::squareToConcentricDisk(Vec2(a, b));
      EXPECT_NEAR(std::hypot(p.x, p.y), 1.0, 1e-6);
      EXPECT_NEAR(std::fabs(p.x), std::fabs(p.y), 1e-6);
      Vec3 v = Warp::squareToCosineHemisphere(Vec2(a, b));
      EXPECT_GT(v.z, 0.f);  // never exactly on the rim
      EXPECT_GT(Warp::squareToCosineHemispherePdf(v), 0.f);
    }
}

TEST(Warp, NarrowConeFromSin2IsAccurate) {
  for (double s2 : {1e-12, 1e-6, 0.5, 1.0}) {
    auto fs2 = float(s2);
    double oneMinusCos = double(fs2) / (1.0 + std::sqrt(1.0 - double(fs2)));
    double expected = 1.0 / (2.0 * kPiD * oneMinusCos);
    for (float a : kExtremes)
      for (float b : kExtremes) {
        SCOPED_TRACE(testing::Message() << "sin2 " << s2 << " u = (" << a << ", " << b << ")");
        Vec3 v = Warp::squareToUniformConeSin2(Vec2(a, b), fs2);
        ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
        EXPECT_NEAR(std::sqrt(double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z), 1.0, 1e-6);
        EXPECT_GE(v.z, 0.f);
        EXPECT_LE(double(v.x) * v.x + double(v.y) * v.y, s2 * (1 + 1e-5));
        float p = Warp::squareToUniformConeSin2Pdf(v, fs2);
        ASSERT_TRUE(std::isfinite(p));
        EXPECT_GT(p, 0.f);
        EXPECT_NEAR(p / expected, 1.0, 1e-6);
      }
  }
  // sin^2 = 1 is the hemisphere
  EXPECT_FLOAT_EQ(Warp::squareToUniformConeSin2Pdf(Vec3(0, 0, 1), 1.f), kInv2Pi);
}

TEST(Warp, NarrowConeFromSin2PassesChiSquare) {
  for (float s2 : {1e-4f, 1e-8f, 1e-12f}) {
    float wMax = float(s2 / (1.0 + std::sqrt(1.0 - double(s2))));
    Chi2Options opt;
    opt.sampleCount = 300000;
    opt.resolution = 31;
    opt.testCount = 3;
    Chi2Result r = chi2Test(
        Chi2Domain::sphere(wMax), [s2](Vec2 u) { return Warp::squareToUniformConeSin2(u, s2); },
        [s2](const Vec3& v) { return double(Warp::squareToUniformConeSin2Pdf(v, s2)); }, opt);
    EXPECT_TRUE(r.accepted) << "sin2 " << s2 << ": chi2 " << r.chi2 << " dof " << r.dof << " p " << r.pValue
                            << " " << r.message;
  }
}

TEST(Warp, TwoDimensionalWarpsReturnZeroZAndDispatchMatchesDirectCalls) {
  Vec2 u(0.3f, 0.8f);
  EXPECT_EQ(Warp::warp(WarpType::Tent, u), Vec3(Warp::squareToTent(u), 0.f));
  EXPECT_EQ(Warp::warp(WarpType::UniformCone, u, 0.7f), Warp::squareToUniformCone(u, 0.7f));
  EXPECT_EQ(Warp::pdf(WarpType::Beckmann, Vec3(0, 0, 1), 0.3f),
            Warp::squareToBeckmannPdf(Vec3(0, 0, 1), 0.3f));
  EXPECT_EQ(Warp::pdf(WarpType::UniformDisk, Vec3(0.1f, 0.1f, 5.f)), kInvPi);  // z ignored for 2-D
}

}  // namespace
}  // namespace penumbra
