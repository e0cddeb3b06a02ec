#include "core/lights/spherical_triangle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "core/lights/polygon_light_test_support.h"
#include "core/sampling/chi2.h"

namespace penumbra {
namespace {

using test::Config;
using test::PlaneBox;

// The triangles of the polygon configurations (a quad's first half), each with its normal turned to
// face x's side of the triangle: solid-angle sampling covers the whole triangle, horizon or not.
std::vector<Config> triangleConfigs() {
  std::vector<Config> out;
  for (Config c : test::polygonConfigs()) {
    c.vertices.resize(3);
    const DVec3 nl = glm::cross(DVec3(c.vertices[1] - c.vertices[0]), DVec3(c.vertices[2] - c.vertices[0]));
    const double side = glm::dot(DVec3(c.vertices[0] - c.x), nl);
    c.n = Vec3(glm::normalize(side > 0 ? nl : -nl));  // every direction towards the triangle has w · n > 0
    c.binOnThePolygon = true;
    out.push_back(c);
  }
  return out;
}

SphericalTriangle mapOf(const Config& c) {
  SphericalTriangle t;
  EXPECT_TRUE(t.init(c.vertices[0], c.vertices[1], c.vertices[2], c.x)) << c.name;
  return t;
}

// χ² on the triangle's own coordinates of the sampled directions against the map's density (or, the
// test of the test, against uniform area density).
Chi2Result triangleChi2(const Config& c, const SphericalTriangle& map, bool areaDensity, int testCount) {
  const PlaneBox plane(c);
  Chi2Options o;
  o.sampleCount = areaDensity ? 200'000 : 1'000'000;
  o.resolution = 40;
  o.seed = 5;
  o.testCount = testCount;
  auto sample = [&](Vec2 u) { return plane.toSquare(map.sampleDirection(u)); };
  auto pdf = [&](const Vec3& p) -> double {
    DVec3 w;
    double factor;
    if (!plane.fromSquare(p.x, p.y, w, factor)) return 0.0;
    return areaDensity ? 2.0 : map.pdfDirection(w) * factor;
  };
  return chi2Test(Chi2Domain::square(0.0, 1.0), sample, pdf, o);
}

TEST(SphericalTriangle, SolidAngleIsTheIntegralOverTheTriangle) {
  for (const Config& c : triangleConfigs()) {
    const SphericalTriangle map = mapOf(c);
    const PlaneBox plane(c);
    const double integral = integratePdf(
        Chi2Domain::square(0.0, 1.0),
        [&](const Vec3& p) {
          DVec3 w;
          double factor;
          return plane.fromSquare(p.x, p.y, w, factor) ? factor / map.solidAngle : 0.0;  // of size 1
        },
        40);
    // The huge one's integrand peaks under x, which the quadrature resolves to a few 1e-6.
    EXPECT_NEAR(integral, 1.0, 1e-5) << c.name;
  }
}

TEST(SphericalTriangle, Chi2OnTheTriangle) {
  const std::vector<Config> all = triangleConfigs();
  for (const Config& c : all) {
    const SphericalTriangle map = mapOf(c);
    const Chi2Result r = triangleChi2(c, map, false, int(all.size()));
    if (std::getenv("PENUMBRA_VERBOSE"))
      std::printf("%-28s Ω %.3g%s chi2 %9.2f dof %5d p %.4f %s\n", c.name, map.solidAngle,
                  map.byArea ? " (by area)" : "", r.chi2, r.dof, r.pValue, r.accepted ? "accept" : "reject");
    EXPECT_TRUE(r.accepted) << c.name << ": " << r.message << " p = " << r.pValue;
  }
}

// Uniform area density is not uniform solid-angle density wherever the distance or the angle to the
// triangle varies: judged by it, the samples are rejected.
TEST(SphericalTriangle, Chi2RejectsTheAreaDensity) {
  const std::vector<Config> all = triangleConfigs();
  for (const Config& c : all) {
    const SphericalTriangle map = mapOf(c);
    if (map.byArea || !c.solidAnglePdfDetectable) continue;
    EXPECT_FALSE(triangleChi2(c, map, true, int(all.size())).accepted) << c.name;
  }
}

// The map's accuracy against the triangle's size: the sub-triangle a b ĉ that u.x chooses (ĉ is the
// sample at u.y → 1) has solid angle u.x Ω. Measured with the map forced on (no area fallback), it holds
// to 1e-6 down to kMinSolidAngle, where the fallback takes over; smaller triangles lose that (1e-4 of
// it at Ω = 4e-9).
TEST(SphericalTriangle, SubTriangleAreaHoldsDownToTheFallbackThreshold) {
  for (double size : {1e-1, 1e-2, 1e-3, 1e-4, 4e-5, 1e-5}) {
    const Vec3 x(0.f), v0(0.3f, 0.2f, 1.f);
    const Vec3 v1 = v0 + Vec3(float(size), 0.f, 0.f), v2 = v0 + Vec3(0.3f * float(size), float(size), 0.f);
    SphericalTriangle map;
    ASSERT_TRUE(map.init(v0, v1, v2, x, 0.0));
    double worst = 0;
    for (int i = 1; i < 64; ++i) {
      const float ux = i / 64.f;
      const DVec3 cHat = map.sampleDirection(Vec2(ux, 1.f));
      // Van Oosterom & Strackee on a, b, ĉ.
      const double sub =
          2 * std::atan2(std::fabs(glm::dot(map.a, glm::cross(map.b, cHat))),
                         1 + glm::dot(map.a, map.b) + glm::dot(map.b, cHat) + glm::dot(cHat, map.a));
      worst = std::max(worst, std::fabs(sub / (ux * map.solidAngle) - 1));
    }
    if (std::getenv("PENUMBRA_VERBOSE"))
      std::printf("Ω %.3g: worst sub-triangle error %.3g\n", map.solidAngle, worst);
    if (map.solidAngle >= SphericalTriangle::kMinSolidAngle) {
      EXPECT_LE(worst, 1e-6) << "Ω " << map.solidAngle;
    }
  }
}

// Below the threshold, area sampling with its exact density: E[1 / pdf] is Ω (unbiased), every sample
// meets the triangle.
TEST(SphericalTriangle, TheAreaFallbackIsUnbiased) {
  const Vec3 x(0.f), v0(0.6f, 0.3f, 0.7f);
  const Vec3 v1 = v0 + Vec3(1e-5f, 0.f, 0.f), v2 = v0 + Vec3(0.f, 1e-5f, 2e-6f);
  SphericalTriangle map;
  ASSERT_TRUE(map.init(v0, v1, v2, x));
  ASSERT_TRUE(map.byArea);
  double sum = 0, sum2 = 0;
  const int n = 1 << 16;
  for (int i = 0; i < n; ++i) {
    const Vec2 u((i + 0.5f) / n, std::fmod(i * 0.618034f, 1.f));
    const double pdf = map.pdfDirection(map.sampleDirection(u));
    ASSERT_GT(pdf, 0.0);
    sum += 1 / pdf, sum2 += 1 / (pdf * pdf);
  }
  const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
  EXPECT_NEAR(mean / map.solidAngle, 1.0, 1e-9 + 4 * se / map.solidAngle);
}

TEST(SphericalTriangle, NothingToSample) {
  SphericalTriangle map;
  EXPECT_FALSE(map.init(Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1), Vec3(0.2f, 0.2f, 1.f)));  // in its plane
  EXPECT_FALSE(map.init(Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(2, 0, 1), Vec3(0)));                // no area
  EXPECT_FALSE(map.init(Vec3(0, 0, 1), Vec3(NAN, 0, 1), Vec3(0, 1, 1), Vec3(0)));
  EXPECT_EQ(map.solidAngle, 0.0);
  // A direction that misses it has density 0.
  ASSERT_TRUE(map.init(Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1), Vec3(0)));
  EXPECT_EQ(map.pdfDirection(DVec3(0, 0, -1)), 0.0);
  EXPECT_GT(map.pdfDirection(glm::normalize(DVec3(0.2, 0.2, 1))), 0.0);
}

}  // namespace
}  // namespace penumbra
