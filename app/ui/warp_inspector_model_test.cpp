// The warp inspector's model without GL: point sets, warped grid lines, the background worker's
// chi-square verdict (cancelled when a newer request arrives) and the histogram panels' images.
#include "app/ui/warp_inspector_model.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "core/math/error.h"
#include "core/sampling/rng.h"
#include "core/sampling/warp_params.h"

using namespace penumbra;
using namespace penumbra::ui;

namespace {

WarpInspectorSettings cosine14() {
  WarpInspectorSettings s;
  s.type = WarpType::CosineHemisphere;
  s.log2Points = 14;
  return s;
}

std::shared_ptr<const WarpVerdict> verdictFor(const WarpInspectorSettings& s) {
  WarpInspectorWorker w;
  w.request(s);
  EXPECT_TRUE(w.waitIdle(60.0));
  auto v = w.verdict();
  EXPECT_TRUE(v && v->settings == s);
  return v;
}

}  // namespace

TEST(WarpInspectorModel, PointSetsAreThePowerOfTwoAndStratified) {
  for (int i = 0; i < kPointSetCount; ++i) {
    auto set = static_cast<PointSet>(i);
    for (int k : {5, 6, 11}) {
      std::vector<Vec2> pts = makePointSet(set, k, 7);
      ASSERT_EQ(pts.size(), size_t(1) << k);
      if (set == PointSet::Independent) continue;
      // one point in each cell of the 2^ceil(k/2) x 2^floor(k/2) grid
      const int nx = 1 << ((k + 1) / 2), ny = 1 << (k / 2);
      std::vector<int> hits(size_t(nx) * ny, 0);
      for (Vec2 p : pts) {
        ASSERT_TRUE(p.x >= 0.f && p.x < 1.f && p.y >= 0.f && p.y < 1.f);
        ++hits[size_t(int(p.y * ny)) * nx + int(p.x * nx)];
      }
      for (int h : hits) EXPECT_EQ(h, 1) << pointSetName(set) << " 2^" << k;
    }
  }
  // independent = the CLI's chi-square stream for the seed (same first sample)
  Rng rng(mix64(7), 7);
  float u1 = rng.nextFloat();
  EXPECT_EQ(makePointSet(PointSet::Independent, 5, 7)[0], Vec2(u1, rng.nextFloat()));
}

TEST(WarpInspectorModel, GridLinesAreSubdividedAndWarped) {
  std::vector<Vec3> lines = warpedGridLines(WarpType::ConcentricDisk, 0.f, 4, 16);
  ASSERT_EQ(lines.size(), size_t(2 * 5 * 16 * 2));
  for (const Vec3& v : lines) EXPECT_LE(v.x * v.x + v.y * v.y, 1.0001f);
  for (const Vec3& v : warpedGridLines(WarpType::UniformSphere, 0.f, 4, 16))
    EXPECT_NEAR(glm::length(v), 1.f, 1e-5f);
}

TEST(WarpInspectorModel, CosineHemisphereAcceptedPanelsCloseMismatchRejected) {
  auto ok = verdictFor(cosine14());
  ASSERT_TRUE(ok);
  EXPECT_TRUE(ok->chi2.accepted) << ok->chi2.message << " p " << ok->chi2.pValue;
  EXPECT_EQ(ok->domain.kind, Chi2Domain::Kind::Sphere);
  HistogramPanels panels = makeHistogramPanels(ok->chi2);
  ASSERT_EQ(panels.width, 2 * panels.height);
  double close = meanAbsoluteDifference(panels.observed, panels.expected);
  std::printf("panels: mean |histogram - density| %.2f / 255 (%dx%d cells)\n", close, panels.width,
              panels.height);
  EXPECT_LT(close, 15.0) << "histogram and density panels differ";

  WarpInspectorSettings bad = cosine14();
  bad.mismatch = true;
  auto rejected = verdictFor(bad);
  ASSERT_TRUE(rejected);
  EXPECT_FALSE(rejected->chi2.accepted) << "p " << rejected->chi2.pValue;
  HistogramPanels badPanels = makeHistogramPanels(rejected->chi2);
  EXPECT_GT(meanAbsoluteDifference(badPanels.observed, badPanels.expected), close * 1.5);
}

TEST(WarpInspectorModel, PlanarWarpsAreHistogrammedOnThePlane) {
  for (WarpType t : {WarpType::ConcentricDisk, WarpType::Tent}) {
    WarpInspectorSettings s;
    s.type = t;
    s.log2Points = 14;
    auto v = verdictFor(s);
    ASSERT_TRUE(v);
    EXPECT_EQ(v->domain.kind, Chi2Domain::Kind::Square) << warpTypeName(t);
    EXPECT_EQ(v->chi2.resX, v->chi2.resY);
    EXPECT_TRUE(v->chi2.accepted) << warpTypeName(t) << ": " << v->chi2.message;
  }
}

TEST(WarpInspectorModel, NewRequestsCancelStaleJobs) {
  WarpInspectorWorker w;
  WarpInspectorSettings s;
  s.type = WarpType::Beckmann;
  s.param = 0.3f;
  s.log2Points = 20;
  w.request(s);
  for (int i = 0; i < 5; ++i) {  // a slider dragged: every frame a new request
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    s.param += 0.05f;
    w.request(s);
  }
  s.log2Points = 12;
  w.request(s);
  ASSERT_TRUE(w.waitIdle(60.0));
  EXPECT_GE(w.cancelledJobs(), 1u);
  ASSERT_TRUE(w.verdict());
  EXPECT_TRUE(w.verdict()->settings == s);
  EXPECT_TRUE(w.points()->settings == s);
  EXPECT_EQ(w.points()->points.size(), size_t(1) << 12);
}

// Values the `penumbra warp` CLI refuses are refused by the inspector with the CLI's message (the
// same checks, core/sampling/warp_params.h), and the settings keep their last valid value, so the
// verdict is never a REJECTED that blames the warp for an invalid parameter.
TEST(WarpInspectorModel, ValuesTheCliRefusesAreRefusedWithItsMessage) {
  WarpInspectorSettings s;
  s.type = WarpType::Beckmann;
  s.param = 0.2f;
  for (double alpha : {0.0, -3.0, 5000.0}) {
    std::string cliMessage;
    try {
      checkedWarpParam(WarpType::Beckmann, true, alpha, "the parameter");
    } catch (const Error& e) {
      cliMessage = e.what();
    }
    ASSERT_FALSE(cliMessage.empty()) << alpha;
    EXPECT_EQ(enterWarpParam(s, alpha), cliMessage);
    EXPECT_EQ(s.param, 0.2f);
  }
  EXPECT_EQ(enterWarpParam(s, 0.0),
            "beckmann: the parameter is the roughness alpha and must be in [1e-06, 1000], got 0");
  EXPECT_EQ(enterWarpParam(s, 0.5), "");
  EXPECT_EQ(s.param, 0.5f);

  s.type = WarpType::UniformCone;
  s.param = 0.5f;
  EXPECT_EQ(
      enterWarpParam(s, 2.0).rfind("uniform-cone: the parameter is cos(theta_max) and must be in [-1, 1)", 0),
      0u);
  EXPECT_EQ(s.param, 0.5f);
  EXPECT_NE(enterWarpParam(s, 1.0), "");
  EXPECT_EQ(enterWarpParam(s, -1.0), "");

  EXPECT_EQ(enterSamplerPixel(s, -5, 0), "pixel -5,0: expected a pixel X,Y with each coordinate 0 to 16383");
  EXPECT_EQ(s.pixelX, 0);
  EXPECT_EQ(enterSamplerPixel(s, 3, 3000000000LL).rfind("pixel 3,3000000000: expected", 0), 0u);
  EXPECT_EQ(enterSamplerPixel(s, 7, 9), "");
  EXPECT_EQ(s.pixelX, 7);
  EXPECT_EQ(s.pixelY, 9);

  EXPECT_NE(enterLog2Points(s, 25), "");
  EXPECT_NE(enterLog2Points(s, 4), "");
  EXPECT_EQ(s.log2Points, 14);
  EXPECT_EQ(enterLog2Points(s, 20), "");
  EXPECT_NE(enterSamplerRequest(s, -1), "");
  EXPECT_NE(enterSamplerRequest(s, 65), "");
  EXPECT_EQ(enterSamplerRequest(s, 64), "");
}

// A BSDF in the inspector: the CLI's samples for the same values and seed, its lobe accepted against
// its own pdf with the rejected draws in their own cell, the pdf at twice the roughness rejected, and
// values the CLI refuses refused with its message.
TEST(WarpInspectorModel, BsdfLobesAreTestedAsTheCliTestsThem) {
  WarpInspectorSettings s = cosine14();
  BsdfWarpInputs in;
  in.type = "roughconductor";
  in.distribution = "ggx";
  in.alpha = 0.3;
  in.incidentDegrees = 60;
  ASSERT_EQ(enterBsdf(s, in), "");
  EXPECT_TRUE(s.bsdf && showsSphere(s));
  const BsdfWarp cli = checkedBsdfWarp(in);
  const std::vector<Vec2> u = makePointSet(s);
  const SampleFunction sample = inspectorSample(s);
  for (size_t i = 0; i < 64; ++i) EXPECT_EQ(sample(u[i]), cli.sample(u[i]));

  auto v = verdictFor(s);
  ASSERT_TRUE(v);
  EXPECT_TRUE(v->chi2.accepted) << v->chi2.message;
  EXPECT_GT(v->chi2.observedRejected, 0.0);  // GGX at 60 degrees reflects some draws below the surface
  EXPECT_GT(v->chi2.expectedRejected, 0.0);
  s.mismatch = true;
  EXPECT_NE(judgeDescription(s).find("twice the roughness"), std::string::npos);
  auto wrong = verdictFor(s);
  ASSERT_TRUE(wrong);
  EXPECT_FALSE(wrong->chi2.accepted);

  WarpInspectorSettings before = s;
  in.alpha = 0.0;
  EXPECT_NE(enterBsdf(s, in).find("--param 0: must be in [0.001, 1000]"), std::string::npos);
  in.alpha = 0.3;
  in.incidentDegrees = 95;
  EXPECT_NE(enterBsdf(s, in).find("--incident 95"), std::string::npos);
  in.incidentDegrees = 60;
  in.distribution = "phong";
  EXPECT_NE(enterBsdf(s, in).find("expected one of: beckmann, ggx"), std::string::npos);
  EXPECT_EQ(s, before);
  // The grid lines leave out segments that end in a rejected draw (the zero vector).
  for (const Vec3& p : warpedGridLines(inspectorSample(s), 8, 16)) EXPECT_NE(p, Vec3(0.f));
}
