#include "core/geometry/parallelogram.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/geometry/procedural_mesh.h"
#include "core/geometry/scene_geometry.h"
#include "core/geometry/triangle.h"
#include "core/math/float_util.h"
#include "core/sampling/random_unit.h"

namespace penumbra {
namespace {

// The assignment's plane.obj: four corners, two triangles sharing the diagonal 4-2, one vertex normal.
TriangleMesh assignmentPlane() {
  TriangleMesh m;
  m.positions = {{1, 0, -1}, {1, 0, 1}, {-1, 0, 1}, {-1, 0, -1}};
  m.normals = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
  m.triangles = {{0, 3, 1}, {3, 2, 1}};
  return m;
}

size_t quadsOf(const TriangleMesh& mesh, size_t* leftoverCount = nullptr) {
  std::vector<Parallelogram> quads;
  std::vector<uint32_t> leftover;
  pairParallelograms(mesh, 0, quads, leftover);
  EXPECT_EQ(quads.size() * 2 + leftover.size(), mesh.triangles.size());
  if (leftoverCount) *leftoverCount = leftover.size();
  return quads.size();
}

TEST(Parallelogram, PairsOnlyWhenNothingVisibleChanges) {
  size_t leftover = 0;
  EXPECT_EQ(quadsOf(assignmentPlane(), &leftover), 1u);
  EXPECT_EQ(leftover, 0u);
  EXPECT_EQ(quadsOf(makeGridPlane(Vec3(-1), Vec3(2, 0, 0), Vec3(0, 3, 1), 1, 1)), 1u);

  TriangleMesh kite = assignmentPlane();  // opposite corners no longer mirror each other
  kite.positions[2] = {-1.5f, 0, 1.2f};
  EXPECT_EQ(quadsOf(kite), 0u);

  TriangleMesh bent = assignmentPlane();  // the fourth corner leaves the plane
  bent.positions[2].y = 1e-3f;
  EXPECT_EQ(quadsOf(bent), 0u);

  TriangleMesh smooth = assignmentPlane();  // different vertex normals would interpolate differently
  smooth.normals[2] = glm::normalize(Vec3(0.1f, 1, 0));
  EXPECT_EQ(quadsOf(smooth), 0u);

  TriangleMesh flipped = assignmentPlane();  // inconsistent winding: the two halves face opposite ways
  flipped.triangles[1] = {3, 1, 2};
  EXPECT_EQ(quadsOf(flipped), 0u);

  // Interior quads of a grid share outer edges with neighbours: merging could open cracks.
  EXPECT_EQ(quadsOf(makeGridPlane(Vec3(-1), Vec3(2, 0, 0), Vec3(0, 2, 0), 3, 1)), 0u);
  TriangleMesh degenerate = assignmentPlane();
  degenerate.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  EXPECT_EQ(quadsOf(degenerate), 0u);
}

// Against the watertight test of the two triangles it replaces: same hits, same t, same primitive,
// same shading data, at three scales.
TEST(Parallelogram, AgreesWithItsTwoTriangles) {
  for (float k : {1e-4f, 1.f, 1e4f}) {
    TriangleMesh mesh = makeGridPlane(Vec3(-1.f, -0.7f, 0.3f) * k, Vec3(2.f, 0.5f, 0.f) * k,
                                      Vec3(0.3f, 1.5f, 0.8f) * k, 1, 1);
    std::vector<Parallelogram> quads;
    std::vector<uint32_t> leftover;
    pairParallelograms(mesh, 0, quads, leftover);
    ASSERT_EQ(quads.size(), 1u);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.5f, 1.5f);
    int hits = 0, disagreements = 0;
    const int n = 50000;
    for (int i = 0; i < n; ++i) {
      Ray ray{Vec3(u(rng), u(rng), u(rng) + 4.f) * k, Vec3(0)};
      ray.d = glm::normalize(Vec3(u(rng), u(rng), 0.5f * u(rng)) * k - ray.o);
      float t, qu, qv;
      const bool quadHit = intersectParallelogram(quads[0], ray, ray.tMax, t, qu, qv);
      TriangleIntersection isect;
      int prim = -1;
      for (int p = 0; p < 2; ++p) {
        const glm::uvec3 tri = mesh.triangles[p];
        if (intersectTriangle(ray, ray.tMax, mesh.positions[tri.x], mesh.positions[tri.y],
                              mesh.positions[tri.z], isect))
          prim = p;
      }
      if (quadHit != (prim >= 0)) {
        ++disagreements;  // only rays through the outline, within rounding
        continue;
      }
      if (!quadHit) continue;
      ++hits;
      EXPECT_NEAR(t, isect.t, 1e-5f * isect.t);
      SurfaceHit a, b;
      fillParallelogramHit(quads[0], ray, t, qu, qv, 7, a);
      fillTriangleHit(mesh, uint32_t(prim), isect, 7, b);
      EXPECT_EQ(a.primId, uint32_t(prim));
      EXPECT_LT(glm::length(a.p - b.p), 1e-5f * k);
      EXPECT_GT(glm::dot(a.ng, b.ng), 1.f - 1e-6f);
      EXPECT_GT(glm::dot(a.ns, b.ns), 1.f - 1e-6f);
      EXPECT_EQ(a.objectId, 7u);
    }
    EXPECT_GT(hits, n / 10);
    EXPECT_LT(disagreements, n / 10000 + 1) << "k=" << k;
  }
}

// Rays leaving the parallelogram (grazing ones included) never hit it again, and rays starting just
// above it towards it always do; at 1e-4, 1 and 1e4 units.
TEST(Parallelogram, NoSelfIntersectionButNearbyHitsSurvive) {
  for (float k : {1e-4f, 1.f, 1e4f}) {
    SceneGeometry g;
    g.addMesh(makeGridPlane(Vec3(-k, -k, -0.5f * k), Vec3(2 * k, 0, 0), Vec3(0.f, 2 * k, 0.3f * k), 1, 1), 1);
    g.build(AccelMode::BruteForce);
    ASSERT_EQ(g.parallelogramCount(), 1u);
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> u(-0.9f, 0.9f);
    for (int i = 0; i < 20000; ++i) {
      Ray ray{Vec3(u(rng), u(rng), 2.f) * k, Vec3(0)};
      ray.d = glm::normalize(Vec3(u(rng) * k, u(rng) * k, -0.5f * k) - ray.o);
      SurfaceHit hit;
      ASSERT_TRUE(g.intersect(ray, hit)) << i;
      Vec3 w = randomUnit(rng);
      if (glm::dot(w, hit.ng) < 0.f) w = -w;
      if (i % 4 == 0) w = glm::normalize(glm::normalize(glm::cross(hit.ng, w)) + hit.ng * 1e-4f);
      if (i % 2) w = -w;  // leaving through the other side
      const Ray leave{offsetRayOrigin(hit.p, hit.ng, hit.offsetScale, w), w};
      SurfaceHit again;
      EXPECT_FALSE(g.intersect(leave, again)) << "k=" << k << " i=" << i << " t=" << again.t;
      EXPECT_FALSE(g.occluded(leave));
      // Even with no offset at all: the conservative plane-side test alone rejects the re-hit.
      EXPECT_FALSE(g.occluded(Ray{hit.p, w})) << "k=" << k << " i=" << i;
      // From 1e-3 of the scale above the hit point straight back down: a hit, at that distance.
      const Vec3 above = hit.p + hit.ng * (1e-3f * k);
      SurfaceHit back;
      ASSERT_TRUE(g.intersect(Ray{above, -hit.ng}, back)) << "k=" << k << " i=" << i;
      EXPECT_NEAR(back.t, 1e-3f * k, 1e-6f * k);
    }
  }
}

TEST(Parallelogram, ParallelAndDegenerateRaysMiss) {
  std::vector<Parallelogram> quads;
  std::vector<uint32_t> leftover;
  pairParallelograms(assignmentPlane(), 0, quads, leftover);
  ASSERT_EQ(quads.size(), 1u);
  float t, u, v;
  EXPECT_FALSE(intersectParallelogram(quads[0], Ray{Vec3(0, 1, 0), Vec3(1, 0, 0)}, INFINITY, t, u, v));
  EXPECT_FALSE(intersectParallelogram(quads[0], Ray{Vec3(0, 0, 0), Vec3(1, 0, 0)}, INFINITY, t, u, v));
  EXPECT_FALSE(intersectParallelogram(quads[0], Ray{Vec3(0, 1, 0), Vec3(NAN, -1, 0)}, INFINITY, t, u, v));
  EXPECT_FALSE(intersectParallelogram(quads[0], Ray{Vec3(0, 1, 0), Vec3(0, -1, 0)}, 0.5f, t, u, v));
  ASSERT_TRUE(intersectParallelogram(quads[0], Ray{Vec3(0.25f, 1, 0.5f), Vec3(0, -1, 0)}, 2.f, t, u, v));
  EXPECT_FLOAT_EQ(t, 1.f);
}

}  // namespace
}  // namespace penumbra
