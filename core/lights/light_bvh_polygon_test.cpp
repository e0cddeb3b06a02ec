// The light BVH over one-sided polygon lights (and spheres beside them): the normal cones that bound
// which way a node's lights emit, the probabilities they give, and that they never give 0 to a light
// that can reach the shading point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/lights/light_bvh.h"
#include "core/lights/light_selection.h"
#include "core/math/frame.h"
#include "core/sampling/rng.h"
#include "core/sampling/warp.h"

namespace penumbra {
namespace {

// Draws in a fixed order (a constructor's arguments are evaluated in an order each compiler picks:
// GCC and clang would build different scenes from one seed).
Vec3 randomIn(Rng& rng, const Vec3& lo, const Vec3& hi) {
  const float x = rng.nextFloat(), y = rng.nextFloat(), z = rng.nextFloat();
  return lo + (hi - lo) * Vec3(x, y, z);
}

Vec3 randomUnit(Rng& rng) {
  const float u = rng.nextFloat(), v = rng.nextFloat();
  return Warp::squareToUniformSphere(Vec2(u, v));
}

// Random triangles in a box, facing every way (`spread` 0) or within ~spread radians of +z.
std::vector<PolygonLight> randomTriangles(int n, uint64_t seed, float facingSpread = 0.f) {
  Rng rng(seed, 3);
  std::vector<PolygonLight> out;
  while (int(out.size()) < n) {
    const Vec3 c = randomIn(rng, Vec3(-10.f, -10.f, 0.f), Vec3(10.f, 10.f, 6.f));
    Vec3 normal = randomUnit(rng);
    if (facingSpread > 0.f) normal = glm::normalize(Vec3(0, 0, 1) + facingSpread * randomUnit(rng));
    const Frame f(normal);
    const float size = 0.05f + rng.nextFloat();
    const bool parallelogram = rng.nextFloat() < 0.3f;
    const Color3 radiance(rng.nextFloat());
    const PolygonLight l =
        PolygonLight::make(c, size * f.s, size * (0.3f * f.s + f.t), parallelogram, radiance);
    if (l.valid()) out.push_back(l);
  }
  return out;
}

// Whether some point of the polygon lies strictly in front of p's horizon while p is in front of it.
bool canLight(const PolygonLight& l, const Vec3& p, const Vec3& n) {
  if (!l.faces(p)) return false;
  if (n == Vec3(0)) return true;
  Vec3 v[4];
  l.vertices(v);
  for (int i = 0; i < l.vertexCount(); ++i)
    if (glm::dot(DVec3(n), DVec3(v[i]) - DVec3(p)) > 0) return true;
  return false;
}

// Checks 300 random shading points; returns how many some light can reach (the checks that bite).
int expectConsistent(const std::vector<PolygonLight>& polygons, uint64_t seed) {
  std::vector<LightSummary> summaries;
  for (const PolygonLight& l : polygons) summaries.push_back(summarizeLight(l));
  const LightBvh bvh = makeLightBvh(summaries);
  Rng rng(seed, 9);
  int reached = 0;
  for (int k = 0; k < 300; ++k) {
    const Vec3 p = randomIn(rng, Vec3(-12.f, -12.f, -2.f), Vec3(12.f, 12.f, 8.f));
    const Vec3 n = k % 3 == 2 ? Vec3(0) : (k % 3 == 0 ? Vec3(0, 0, 1) : randomUnit(rng));
    double sum = 0;
    for (uint32_t i = 0; i < polygons.size(); ++i) {
      const double pmf = bvh.pmf(p, n, i);
      EXPECT_TRUE(std::isfinite(pmf) && pmf >= 0.0 && pmf <= 1.0);
      sum += pmf;
      if (polygonLightPower(polygons[i]) > 0.0 && canLight(polygons[i], p, n))
        EXPECT_GT(pmf, 0.0) << "light " << i << " can reach the point but is never picked";
    }
    if (sum > 0.0) {
      ++reached;
      EXPECT_NEAR(sum, 1.0, 1e-12);
      for (int j = 0; j < 10; ++j) {
        const LightPick pick = bvh.pick(p, n, rng.nextDouble());
        EXPECT_GT(pick.pmf, 0.0);
        EXPECT_NEAR(pick.pmf, bvh.pmf(p, n, pick.light), 1e-12 * pick.pmf);
      }
    }
  }
  EXPECT_GT(reached, 0);
  return reached;
}

TEST(LightBvhPolygons, PmfsSumToOneMatchPicksAndNeverMissALightThatCanReach) {
  int reached = 0;
  for (int n : {1, 2, 7, 100, 1000})
    reached += expectConsistent(randomTriangles(n, 40 + uint64_t(n)), uint64_t(n));
  // All facing up: the cones stay narrow and exclude much more.
  reached += expectConsistent(randomTriangles(300, 77, 0.2f), 5);
  // A single small triangle may face away from most of the box; together the cases reach most points.
  EXPECT_GT(reached, 900);
}

TEST(LightBvhPolygons, LightsFacingAwayGetNothingAndOrientationShiftsTheChoice) {
  // Two equal squares 2 above p: one faces down towards it, the other up, away from it.
  const PolygonLight down =
      PolygonLight::make(Vec3(-1, -1, 2), Vec3(0, 1, 0), Vec3(1, 0, 0), true, Color3(1));
  const PolygonLight up = PolygonLight::make(Vec3(1, -1, 2), Vec3(1, 0, 0), Vec3(0, 1, 0), true, Color3(1));
  ASSERT_LT(down.n.z, 0.f);
  ASSERT_GT(up.n.z, 0.f);
  const LightBvh bvh = makeLightBvh(std::vector<LightSummary>{summarizeLight(down), summarizeLight(up)});
  EXPECT_EQ(bvh.pmf(Vec3(0), Vec3(0, 0, 1), 1), 0.0);
  EXPECT_DOUBLE_EQ(bvh.pmf(Vec3(0), Vec3(0, 0, 1), 0), 1.0);
  // Seen from above both, only the upward one can reach.
  EXPECT_DOUBLE_EQ(bvh.pmf(Vec3(0, 0, 5), Vec3(0, 0, -1), 1), 1.0);
  // The root's cone holds both normals: every direction.
  EXPECT_EQ(bvh.nodes[0].cosConeAngle, -1.f);
}

TEST(LightBvhPolygons, JoinedConesHoldEveryDirectionOfBoth) {
  Rng rng(5, 6);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 a = randomUnit(rng), b = randomUnit(rng);
    float cosA = std::cos(1.6f * rng.nextFloat()), cosB = std::cos(1.6f * rng.nextFloat());
    if (k % 10 == 0) cosA = 1.f;  // a single direction
    Vec3 axis = a;
    float cosAngle = cosA;
    joinCones(axis, cosAngle, b, cosB);
    for (int j = 0; j < 20; ++j) {
      // A direction on the rim of either cone.
      const bool first = j % 2 == 0;
      const Frame f(first ? a : b);
      const float c = first ? cosA : cosB, s = std::sqrt(std::max(0.f, 1.f - c * c));
      const float phi = 6.2831853f * rng.nextFloat();
      const Vec3 w = f.toWorld(Vec3(s * std::cos(phi), s * std::sin(phi), c));
      EXPECT_GE(glm::dot(axis, w), cosAngle - 1e-5f) << k;
    }
    // Not wider than needed: the wider cone when it holds the other, else half of both side by side.
    const double thetaA = std::acos(double(cosA)), thetaB = std::acos(double(cosB));
    const double spanned = std::acos(std::clamp(double(glm::dot(a, b)), -1.0, 1.0)) + thetaA + thetaB;
    if (cosAngle > -1.f) {
      EXPECT_LE(std::acos(double(cosAngle)), std::max({thetaA, thetaB, 0.5 * spanned}) + 1e-5) << k;
    }
  }
  // A cone of every direction absorbs anything.
  Vec3 axis(0, 0, 1);
  float cosAngle = 0.5f;
  joinCones(axis, cosAngle, Vec3(1, 0, 0), -1.f);
  EXPECT_EQ(cosAngle, -1.f);
}

}  // namespace
}  // namespace penumbra
