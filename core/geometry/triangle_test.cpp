#include "core/geometry/triangle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/geometry/procedural_mesh.h"
#include "core/math/float_util.h"

namespace penumbra {
namespace {

TEST(Triangle, HitMissAndBarycentrics) {
  Vec3 p0(0, 0, 0), p1(1, 0, 0), p2(0, 1, 0);
  TriangleIntersection isect;
  Ray ray{Vec3(0.25f, 0.25f, 1.f), Vec3(0, 0, -1)};
  ASSERT_TRUE(intersectTriangle(ray, ray.tMax, p0, p1, p2, isect));
  EXPECT_FLOAT_EQ(isect.t, 1.f);
  EXPECT_FLOAT_EQ(isect.b1, 0.25f);
  EXPECT_FLOAT_EQ(isect.b2, 0.25f);
  EXPECT_FLOAT_EQ(isect.b0, 0.5f);
  // Back face is hit too.
  Ray back{Vec3(0.25f, 0.25f, -1.f), Vec3(0, 0, 1)};
  EXPECT_TRUE(intersectTriangle(back, back.tMax, p0, p1, p2, isect));
  // Misses: outside, behind, beyond tMax, parallel.
  EXPECT_FALSE(intersectTriangle(Ray{Vec3(0.75f, 0.75f, 1.f), Vec3(0, 0, -1)}, INFINITY, p0, p1, p2, isect));
  EXPECT_FALSE(intersectTriangle(Ray{Vec3(0.25f, 0.25f, 1.f), Vec3(0, 0, 1)}, INFINITY, p0, p1, p2, isect));
  EXPECT_FALSE(intersectTriangle(ray, 0.99f, p0, p1, p2, isect));
  EXPECT_FALSE(intersectTriangle(Ray{Vec3(-1, 0.2f, 0), Vec3(1, 0, 0)}, INFINITY, p0, p1, p2, isect));
  // Degenerate triangle.
  EXPECT_FALSE(intersectTriangle(ray, INFINITY, p0, p1, p1 * 0.5f, isect));
}

TEST(Triangle, FillHitNormals) {
  TriangleMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  mesh.triangles = {{0, 1, 2}};
  TriangleIntersection isect{2.f, 0.2f, 0.3f, 0.5f};
  SurfaceHit hit;
  fillTriangleHit(mesh, 0, isect, 9, hit);
  EXPECT_EQ(hit.objectId, 9u);
  EXPECT_EQ(hit.ng, Vec3(0, 0, 1));  // counter-clockwise winding
  EXPECT_EQ(hit.ns, Vec3(0, 0, 1));
  EXPECT_NEAR(hit.p.x, 0.3f, 1e-7f);
  EXPECT_NEAR(hit.p.y, 0.5f, 1e-7f);
  mesh.normals = {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  fillTriangleHit(mesh, 0, isect, 9, hit);
  EXPECT_NEAR(glm::length(hit.ns), 1.f, 1e-6f);
  EXPECT_NEAR(hit.ns.x / hit.ns.z, 0.2f / 0.5f, 1e-6f);
}

// Rays aimed exactly at points of an edge shared by two triangles (and at the shared vertex) hit at
// least one of them: never neither.
TEST(Triangle, WatertightSharedEdges) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (float k : {1e-4f, 1.f, 1e4f}) {
    for (int i = 0; i < 20000; ++i) {
      // Two triangles sharing the edge a-b, randomly placed.
      Vec3 a = (Vec3(u(rng), u(rng), u(rng)) - 0.5f) * k;
      Vec3 b = (Vec3(u(rng), u(rng), u(rng)) - 0.5f) * k;
      Vec3 c = (Vec3(u(rng), u(rng), u(rng)) - 0.5f) * k;
      Vec3 mid = 0.5f * (a + b);
      Vec3 e = glm::cross(b - a, c - a);
      if (glm::length(e) < 1e-3f * k * k) continue;
      // Mirror c across the edge (in the plane) to get the other triangle's apex.
      Vec3 ab = glm::normalize(b - a);
      Vec3 ac = c - a;
      Vec3 along = glm::dot(ac, ab) * ab;
      Vec3 dd = a + along - (ac - along);
      float s = 0.01f + 0.98f * u(rng);  // vertices need a full fan: see WatertightOnGridPlane
      Vec3 target = a + s * (b - a);
      Vec3 o = mid + (Vec3(u(rng), u(rng), u(rng)) - 0.5f) * (4.f * k);
      Vec3 d = glm::normalize(target - o);
      Ray ray{o, d};
      TriangleIntersection i1, i2;
      bool h1 = intersectTriangle(ray, INFINITY, a, b, c, i1);
      bool h2 = intersectTriangle(ray, INFINITY, b, a, dd, i2);
      // Ray parallel to the plane or origin on it: not a crack.
      Vec3 n = glm::normalize(e);
      if (std::abs(glm::dot(d, n)) < 1e-3f || std::abs(glm::dot(o - a, n)) < 1e-3f * k) continue;
      ASSERT_TRUE(h1 || h2) << "k=" << k << " i=" << i;
    }
  }
}

TEST(Triangle, WatertightOnGridPlane) {
  // Rays through the vertices and edges of a fine grid: none falls through.
  for (float k : {1e-4f, 1.f, 1e4f}) {
    TriangleMesh grid = makeGridPlane(Vec3(-k, -k, 0), Vec3(2 * k, 0, 0), Vec3(0, 2 * k, 0), 16, 16);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    for (size_t v = 0; v < grid.positions.size(); ++v) {
      const Vec3 target = grid.positions[v];
      if (std::abs(target.x) >= k || std::abs(target.y) >= k) continue;  // boundary vertices
      Vec3 o = Vec3(u(rng) * k, u(rng) * k, (0.5f + std::abs(u(rng))) * k);
      Ray ray{o, glm::normalize(target - o)};
      int hits = 0;
      for (size_t t = 0; t < grid.triangles.size(); ++t) {
        TriangleIntersection isect;
        glm::uvec3 tri = grid.triangles[t];
        hits += intersectTriangle(ray, INFINITY, grid.positions[tri.x], grid.positions[tri.y],
                                  grid.positions[tri.z], isect);
      }
      EXPECT_GE(hits, 1) << "k=" << k << " vertex " << v;
    }
  }
}

TEST(Triangle, NoSelfIntersectionAfterOffset) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  for (float k : {1e-4f, 1.f, 1e4f}) {
    int tested = 0;
    for (int i = 0; i < 20000; ++i) {
      TriangleMesh mesh;
      Vec3 shift = Vec3(u(rng), u(rng), u(rng)) * (3.f * k);
      mesh.positions = {shift + Vec3(u(rng), u(rng), u(rng)) * k, shift + Vec3(u(rng), u(rng), u(rng)) * k,
                        shift + Vec3(u(rng), u(rng), u(rng)) * k};
      mesh.triangles = {{0, 1, 2}};
      const Vec3 &p0 = mesh.positions[0], &p1 = mesh.positions[1], &p2 = mesh.positions[2];
      if (glm::length(glm::cross(p1 - p0, p2 - p0)) < 1e-2f * k * k) continue;
      Vec3 o = shift + Vec3(u(rng), u(rng), u(rng)) * (3.f * k);
      float b1 = std::abs(u(rng)), b2 = std::abs(u(rng));
      if (b1 + b2 > 1.f) b1 = 1.f - b1, b2 = 1.f - b2;
      Vec3 target = p0 + b1 * (p1 - p0) + b2 * (p2 - p0);
      Ray ray{o, glm::normalize(target - o)};
      TriangleIntersection isect;
      if (!intersectTriangle(ray, INFINITY, p0, p1, p2, isect)) continue;
      SurfaceHit hit;
      fillTriangleHit(mesh, 0, isect, 0, hit);
      // Any direction leaving on either side, including grazing ones.
      Vec3 w = glm::normalize(Vec3(u(rng), u(rng), u(rng)));
      if (i % 4 == 0) {  // nearly tangent
        w = glm::normalize(glm::cross(hit.ng, w)) + hit.ng * (1e-4f * u(rng));
        w = glm::normalize(w);
      }
      Vec3 origin = offsetRayOrigin(hit.p, hit.ng, hit.offsetScale, w);
      TriangleIntersection again;
      EXPECT_FALSE(intersectTriangle(Ray{origin, w}, INFINITY, p0, p1, p2, again))
          << "k=" << k << " i=" << i << " t=" << again.t;
      ++tested;
    }
    EXPECT_GT(tested, 5000);
  }
}

}  // namespace
}  // namespace penumbra
