#include "core/geometry/scene_geometry.h"
#include "core/sampling/random_unit.h"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <memory>
#include <random>
#include <thread>
#include <vector>

#include "core/geometry/procedural_mesh.h"
#include "core/math/float_util.h"

namespace penumbra {
namespace {

// Triangle mode × sphere mode: every way the two kinds of primitive can be split between the flat
// loops and the BVH.
constexpr std::pair<AccelMode, AccelMode> kAccelCombinations[] = {
    {AccelMode::BruteForce, AccelMode::BruteForce},
    {AccelMode::Embree, AccelMode::BruteForce},
    {AccelMode::BruteForce, AccelMode::Embree},
    {AccelMode::Embree, AccelMode::Embree}};

SceneGeometry rockScene(AccelMode mode, int subdivisions) {
  SceneGeometry g;
  g.addMesh(makeRockMesh(subdivisions, 42), 3);
  g.addSphere(Sphere{Vec3(1.5f, 0, 0), 0.3f}, 5);
  g.addMesh(makeGridPlane(Vec3(-4, -4, -1.2f), Vec3(8, 0, 0), Vec3(0, 8, 0), 2, 2), 8);
  g.build(mode);
  return g;
}

TEST(SceneGeometry, EmptyScene) {
  SceneGeometry g;
  g.build();
  SurfaceHit hit;
  EXPECT_FALSE(g.intersect(Ray{Vec3(0), Vec3(0, 0, 1)}, hit));
  EXPECT_FALSE(g.occluded(Ray{Vec3(0), Vec3(0, 0, 1)}));
  EXPECT_TRUE(g.bounds().empty());
  EXPECT_FALSE(g.usesEmbree());
}

TEST(SceneGeometry, AutoModePaysOnlyForWhatItNeeds) {
  SceneGeometry small;
  small.addSphere(Sphere{Vec3(0), 1}, 0);
  small.addMesh(makeGridPlane(Vec3(-1, -1, -1), Vec3(2, 0, 0), Vec3(0, 2, 0), 1, 1), 1);
  small.build();
  EXPECT_FALSE(small.usesEmbree());
  EXPECT_EQ(small.triangleCount(), 2u);
  SceneGeometry big;
  big.addMesh(makeRockMesh(1, 1), 0);  // 80 triangles
  big.build();
  EXPECT_TRUE(big.usesEmbree());
  EXPECT_EQ(big.triangleCount(), 80u);
}

TEST(SceneGeometry, NearestOfSpheresAndTrianglesWithIds) {
  SceneGeometry g;
  g.addSphere(Sphere{Vec3(0, 0, 0), 1}, 10);
  g.addSphere(Sphere{Vec3(0, 0, 5), 1}, 11);
  g.addMesh(makeGridPlane(Vec3(-10, -10, -2), Vec3(20, 0, 0), Vec3(0, 20, 0), 1, 1), 12);
  for (AccelMode mode : {AccelMode::BruteForce, AccelMode::Embree}) {
    g.build(mode);
    EXPECT_EQ(g.usesEmbree(), mode == AccelMode::Embree);
    SurfaceHit hit;
    ASSERT_TRUE(g.intersect(Ray{Vec3(0, 0, 10), Vec3(0, 0, -1)}, hit));
    EXPECT_EQ(hit.objectId, 11u);
    EXPECT_FLOAT_EQ(hit.t, 4.f);
    ASSERT_TRUE(g.intersect(Ray{Vec3(0, 0, 3), Vec3(0, 0, -1)}, hit));
    EXPECT_EQ(hit.objectId, 10u);
    ASSERT_TRUE(g.intersect(Ray{Vec3(3, 0, 3), Vec3(0, 0, -1)}, hit));
    EXPECT_EQ(hit.objectId, 12u);
    EXPECT_FLOAT_EQ(hit.t, 5.f);
    EXPECT_EQ(hit.ng, Vec3(0, 0, 1));
    EXPECT_FALSE(g.occluded(Ray{Vec3(3, 0, 3), Vec3(0, 0, -1), 0.f, 4.99f}));
    EXPECT_TRUE(g.occluded(Ray{Vec3(3, 0, 3), Vec3(0, 0, -1), 0.f, 5.01f}));
  }
  Bounds b = g.bounds();
  EXPECT_EQ(b.min, Vec3(-10, -10, -2));
  EXPECT_EQ(b.max, Vec3(10, 10, 6));
}

TEST(SceneGeometry, SpheresGoToTheBvhAboveTheThreshold) {
  if (sphereAccelFromEnvironment() != AccelMode::Auto) GTEST_SKIP() << "PENUMBRA_SPHERE_ACCEL forces a path";
  for (size_t n : {kBruteForceMaxSpheres, kBruteForceMaxSpheres + 1}) {
    SceneGeometry g;
    for (size_t i = 0; i < n; ++i) g.addSphere(Sphere{Vec3(float(3 * i), 0, 0), 1}, uint32_t(i));
    g.build(AccelMode::Auto, AccelMode::Auto);
    EXPECT_EQ(g.spheresUseBvh(), n > kBruteForceMaxSpheres);
    EXPECT_FALSE(g.usesEmbree());
  }
}

// Spheres in the BVH, alone or sharing it with triangles, or beside flat triangles and parallelograms:
// the same nearest hits (bit for bit: the BVH calls the same sphere test) and the same occlusion,
// with and without the skipped sphere of a shadow ray.
TEST(SceneGeometry, SphereBvhAgreesWithTheFlatLoopBitForBit) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  auto build = [](AccelMode mode, AccelMode sphereMode) {
    SceneGeometry g;
    std::mt19937 placement(13);
    std::uniform_real_distribution<float> p(-1.f, 1.f);
    for (uint32_t i = 0; i < 300; ++i)
      g.addSphere(
          Sphere{Vec3(p(placement), p(placement), p(placement)) * 3.f, 0.05f + 0.3f * std::abs(p(placement))},
          i);
    g.addMesh(makeGridPlane(Vec3(-4, -4, -3.5f), Vec3(8, 0, 0), Vec3(0, 8, 0), 1, 1), 1000);
    g.addMesh(makeRockMesh(1, 5), 1001);
    g.build(mode, sphereMode);
    return g;
  };
  const SceneGeometry reference = build(AccelMode::BruteForce, AccelMode::BruteForce);
  ASSERT_FALSE(reference.spheresUseBvh());
  for (AccelMode mode : {AccelMode::BruteForce, AccelMode::Embree}) {
    const SceneGeometry g = build(mode, AccelMode::Embree);
    ASSERT_TRUE(g.spheresUseBvh());
    const SceneGeometry sameTriangles = build(mode, AccelMode::BruteForce);
    int sphereHits = 0;
    for (int i = 0; i < 20000; ++i) {
      Ray ray{randomUnit(rng) * 6.f, Vec3(0)};
      ray.d = glm::normalize(Vec3(u(rng), u(rng), u(rng)) * 2.f - ray.o);
      if (i % 3 == 0) ray.tMax = 3.f + 4.f * std::abs(u(rng));
      SurfaceHit a, b;
      const bool ha = sameTriangles.intersect(ray, a), hb = g.intersect(ray, b);
      ASSERT_EQ(ha, hb) << i;
      const int32_t skip = int32_t(i % 300);
      EXPECT_EQ(sameTriangles.occluded(ray, skip), g.occluded(ray, skip)) << i;
      EXPECT_EQ(sameTriangles.occluded(ray), g.occluded(ray)) << i;
      if (!ha) continue;
      EXPECT_EQ(a.objectId, b.objectId) << i;
      EXPECT_EQ(a.t, b.t) << i;
      EXPECT_EQ(a.p, b.p) << i;
      EXPECT_EQ(a.ng, b.ng) << i;
      EXPECT_EQ(a.offsetScale, b.offsetScale) << i;
      sphereHits += a.objectId < 300;
      if (mode == AccelMode::BruteForce) {  // the same triangle path as the reference too
        SurfaceHit r;
        ASSERT_TRUE(reference.intersect(ray, r));
        EXPECT_EQ(r.objectId, b.objectId);
        EXPECT_EQ(r.t, b.t);
      }
    }
    EXPECT_GT(sphereHits, 5000);
  }
}

// Rays from a point 1e-6 r below a sphere (a receiver touching a light) hit it at t ~ 1e-6 r on
// both paths: the BVH's box test must not cull a sphere that the ray starts next to.
TEST(SceneGeometry, RaysFromJustOutsideASphereHitItInTheBvh) {
  std::mt19937 rng(14);
  for (AccelMode sphereMode : {AccelMode::BruteForce, AccelMode::Embree}) {
    SceneGeometry g;
    g.addMesh(makeGridPlane(Vec3(-10, -10, 0), Vec3(20, 0, 0), Vec3(0, 20, 0), 1, 1), 0);
    g.addSphere(Sphere{Vec3(0.31f, 0.17f, 1.0000009536743164f), 1.f}, 1);
    g.build(AccelMode::Auto, sphereMode);
    const Vec3 x(0.31f, 0.17f, 0.f);
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
      Vec3 w = randomUnit(rng);
      w.z = std::abs(w.z);
      SurfaceHit hit;
      const Ray ray{offsetRayOrigin(x, Vec3(0, 0, 1), 10.f, w), w};
      hits += g.intersect(ray, hit) && hit.objectId == 1;
    }
    EXPECT_GT(hits, 1900) << (sphereMode == AccelMode::Embree ? "bvh" : "brute force");
  }
}

// A shadow ray through the centre of a sphere is blocked by it unless it is the skipped one.
TEST(SceneGeometry, ShadowRaysSkipTheirLightInTheBvh) {
  for (AccelMode sphereMode : {AccelMode::BruteForce, AccelMode::Embree}) {
    SceneGeometry g;
    for (uint32_t i = 0; i < 40; ++i) g.addSphere(Sphere{Vec3(float(3 * i), 0, 0), 1}, i);
    g.build(AccelMode::Auto, sphereMode);
    const Ray through{Vec3(6, 0, -5), Vec3(0, 0, 1), 0.f, 10.f};
    EXPECT_TRUE(g.occluded(through));
    EXPECT_TRUE(g.occluded(through, 1));
    EXPECT_FALSE(g.occluded(through, 2));
    // An empty segment is blocked by nothing (a light nearer than the origin's offset).
    EXPECT_FALSE(g.occluded(Ray{Vec3(6, 0, -5), Vec3(0, 0, 1), 0.f, -1e-5f}));
  }
}

TEST(SceneGeometry, MoveKeepsEmbreeScene) {
  SceneGeometry a = rockScene(AccelMode::Embree, 2);
  SceneGeometry b = std::move(a);
  EXPECT_TRUE(b.usesEmbree());
  SurfaceHit hit;
  EXPECT_TRUE(b.intersect(Ray{Vec3(0, 0, 5), Vec3(0, 0, -1)}, hit));
  SceneGeometry c;
  c = std::move(b);
  EXPECT_TRUE(c.intersect(Ray{Vec3(0, 0, 5), Vec3(0, 0, -1)}, hit));
  EXPECT_EQ(hit.objectId, 3u);
}

TEST(SceneGeometry, BruteForceAndEmbreeAgree) {
  SceneGeometry brute = rockScene(AccelMode::BruteForce, 4);  // 5120 rock triangles
  SceneGeometry embree = rockScene(AccelMode::Embree, 4);
  ASSERT_FALSE(brute.usesEmbree());
  ASSERT_TRUE(embree.usesEmbree());
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  int hits = 0, primMismatch = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    Ray ray;
    if (i % 2 == 0) {  // from outside towards the rock
      ray.o = randomUnit(rng) * 4.f;
      ray.d = glm::normalize(Vec3(u(rng), u(rng), u(rng)) * 0.8f - ray.o);
    } else {  // from inside the rock outwards (crevices, plane, sphere)
      ray.o = Vec3(u(rng), u(rng), u(rng)) * 0.3f;
      ray.d = randomUnit(rng);
    }
    SurfaceHit hb, he;
    bool b = brute.intersect(ray, hb);
    bool e = embree.intersect(ray, he);
    ASSERT_EQ(b, e) << i;
    EXPECT_EQ(brute.occluded(ray), b);
    EXPECT_EQ(embree.occluded(ray), e);
    if (!b) continue;
    ++hits;
    EXPECT_EQ(hb.objectId, he.objectId) << i;
    EXPECT_NEAR(hb.t, he.t, 1e-5f * std::max(1.f, hb.t)) << i;
    EXPECT_LT(glm::length(hb.p - he.p), 1e-5f) << i;
    if (hb.primId != he.primId) {
      ++primMismatch;  // ray through a shared edge: either triangle is right
    } else {
      EXPECT_EQ(hb.ng, he.ng);
      EXPECT_LT(glm::length(hb.ns - he.ns), 1e-4f);  // Embree's u, v differ in the last bits
    }
    // Occlusion limited to just before / after the hit.
    Ray before = ray;
    before.tMax = hb.t * (1.f - 1e-4f);
    EXPECT_FALSE(brute.occluded(before)) << i;
    EXPECT_FALSE(embree.occluded(before)) << i;
  }
  EXPECT_GT(hits, n * 9 / 10);
  EXPECT_LT(primMismatch, n / 100);
}

// occludedMany answers each active ray as occluded() does (inactive ones: not blocked), for a skipped
// sphere and none, on every split of the primitives between the flat loops and the BVH; rays in fans
// from shading points as a packet's shadow rays are, some of them empty segments.
TEST(SceneGeometry, OccludedManyAnswersAsOccludedDoes) {
  for (const auto& [mode, sphereMode] : kAccelCombinations) {
    SceneGeometry g;
    g.addMesh(makeRockMesh(3, 9), 0);
    g.addMesh(makeGridPlane(Vec3(-20, -1, -20), Vec3(0, 0, 40), Vec3(40, 0, 0), 2, 2), 1);
    for (uint32_t i = 0; i < 40; ++i)
      g.addSphere(Sphere{Vec3(-2.f + 0.1f * float(i), 0.8f + 0.02f * float(i % 7), 1.2f), 0.08f}, 2 + i);
    g.build(mode, sphereMode);
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    int blocked = 0, tested = 0;
    for (int packet = 0; packet < 200; ++packet) {
      const size_t n = 1 + size_t(packet) % SceneGeometry::kOccludedManyRays;
      const Vec3 target(u(rng) * 2.f, 1.f + u(rng), 1.2f + u(rng));
      Ray rays[SceneGeometry::kOccludedManyRays];
      bool active[SceneGeometry::kOccludedManyRays], answers[SceneGeometry::kOccludedManyRays];
      for (size_t i = 0; i < n; ++i) {
        const Vec3 o(u(rng) * 3.f, -0.999f, u(rng) * 3.f);
        const Vec3 d = target - o;
        const float length = glm::length(d);
        rays[i] = Ray{o, d / length, 0.f, packet % 5 == 0 ? 0.f : length};
        active[i] = (packet + int(i)) % 7 != 0;
      }
      const int32_t skip = packet % 2 ? int32_t(packet % 40) : -1;
      g.occludedMany(rays, active, n, skip, answers);
      for (size_t i = 0; i < n; ++i) {
        EXPECT_EQ(answers[i], active[i] && g.occluded(rays[i], skip)) << "packet " << packet << " ray " << i;
        tested += active[i];
        blocked += answers[i];
      }
    }
    EXPECT_GT(blocked, tested / 20);
    EXPECT_LT(blocked, tested - tested / 20);
  }
}

// AO-style rays leaving the surface of a convex shape never hit that shape again.
TEST(SceneGeometry, NoSelfIntersectionOnConvexShapes) {
  for (auto [mode, sphereMode] : kAccelCombinations) {
    for (float k : {1e-4f, 1.f, 1e4f}) {
      SceneGeometry g;
      g.addMesh(makeGridPlane(Vec3(-k, -k, -0.5f * k), Vec3(2 * k, 0, 0), Vec3(0, 2 * k, 0), 4, 4), 1);
      g.addSphere(Sphere{Vec3(0.1f, 0.2f, 0.3f) * k, 0.5f * k}, 2);
      g.build(mode, sphereMode);
      ASSERT_EQ(g.spheresUseBvh(), sphereMode == AccelMode::Embree);
      std::mt19937 rng(8);
      std::uniform_real_distribution<float> u(-1.f, 1.f);
      int tested = 0;
      for (int i = 0; i < 20000; ++i) {
        Ray ray{Vec3(u(rng), u(rng), 1.f) * (2.f * k), Vec3(0)};
        ray.d = glm::normalize(Vec3(u(rng) * k, u(rng) * k, -0.5f * k) - ray.o);
        SurfaceHit hit;
        if (!g.intersect(ray, hit)) continue;
        Vec3 w = randomUnit(rng);
        if (glm::dot(w, hit.ng) < 0.f) w = -w;
        if (i % 4 == 0) w = glm::normalize(glm::normalize(glm::cross(hit.ng, w)) + hit.ng * 1e-4f);
        Ray ao{offsetRayOrigin(hit.p, hit.ng, hit.offsetScale, w), w};
        SurfaceHit again;
        if (g.intersect(ao, again)) {
          // The only legitimate hit: from the plane, the sphere.
          EXPECT_NE(again.objectId, hit.objectId) << "k=" << k << " i=" << i << " t=" << again.t;
        }
        ++tested;
      }
      EXPECT_GT(tested, 10000);
    }
  }
}

bool sameHit(const SurfaceHit& a, const SurfaceHit& b) {
  auto bits = [](const Vec3& v) {
    return std::array{std::bit_cast<uint32_t>(v.x), std::bit_cast<uint32_t>(v.y),
                      std::bit_cast<uint32_t>(v.z)};
  };
  return std::bit_cast<uint32_t>(a.t) == std::bit_cast<uint32_t>(b.t) && bits(a.p) == bits(b.p) &&
         bits(a.ng) == bits(b.ng) && bits(a.ns) == bits(b.ns) &&
         std::bit_cast<uint32_t>(a.offsetScale) == std::bit_cast<uint32_t>(b.offsetScale) &&
         a.objectId == b.objectId && a.primId == b.primId;
}

// Counts the rays whose intersectMany() answer differs from intersect()'s in any bit, and of those
// the ones whose difference is only which of two surfaces within 4 ulps of one distance is reported.
struct Mismatches {
  int any = 0;
  int tiesAtTheSameDistance = 0;
};
Mismatches intersectManyMismatches(const SceneGeometry& g, const std::vector<Ray>& rays) {
  std::vector<SurfaceHit> many(rays.size());
  std::unique_ptr<bool[]> found(new bool[rays.size()]);
  g.intersectMany(rays.data(), rays.size(), many.data(), found.get());
  Mismatches m;
  for (size_t i = 0; i < rays.size(); ++i) {
    SurfaceHit one;
    const bool hit = g.intersect(rays[i], one);
    if (hit == found[i] && (!hit || sameHit(one, many[i]))) continue;
    ++m.any;
    m.tiesAtTheSameDistance += hit && found[i] && std::abs(one.t - many[i].t) <= 0x1p-21f * one.t &&
                               one.objectId != many[i].objectId;
  }
  return m;
}

// Camera-like fans of rays (neighbours nearly parallel, as a stream of one row's camera rays), aimed
// at random points and, for every third ray, at a grid point or a point on a grid line exactly.
std::vector<Ray> cameraFans(std::mt19937& rng, const Vec3& eye, float gridSize, int cells, int count) {
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::uniform_int_distribution<int> cell(0, cells);
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    const float step = gridSize / float(cells);
    Vec3 target(u(rng) * gridSize, u(rng) * gridSize, 0.f);
    if (i % 3 == 0) target.x = float(cell(rng)) * step;
    if (i % 6 == 0) target.y = float(cell(rng)) * step;
    if (i % 9 == 0) target.y = target.x;  // the cells' diagonals
    rays.push_back(Ray{eye, glm::normalize(target - eye)});
  }
  return rays;
}

// A stream of rays finds what the rays find one by one, bit for bit, also where a ray meets the edge
// two triangles share (a stream breaks that tie by its own traversal order).
TEST(SceneGeometry, IntersectManyIsIntersectBitForBit) {
  std::mt19937 rng(12);
  for (AccelMode sphereMode : {AccelMode::BruteForce, AccelMode::Embree}) {
    SceneGeometry g;
    g.addMesh(makeRockMesh(5, 42), 3);
    g.addSphere(Sphere{Vec3(1.5f, 0, 0.5f), 0.3f}, 5);
    g.addMesh(makeGridPlane(Vec3(0, 0, 0), Vec3(16, 0, 0), Vec3(0, 16, 0), 16, 16), 8);
    g.build(AccelMode::Embree, sphereMode);
    for (const Vec3& eye : {Vec3(8, 8, 20), Vec3(-3, 5, 4), Vec3(2, 2, 0.5f), Vec3(8.5f, 8.5f, 3)}) {
      const std::vector<Ray> rays = cameraFans(rng, eye, 16.f, 16, 3000);
      EXPECT_EQ(intersectManyMismatches(g, rays).any, 0) << "eye " << eye.x << "," << eye.y << "," << eye.z;
    }
  }
  // Few triangles: the flat loops alone, no stream.
  SceneGeometry flat;
  flat.addMesh(makeGridPlane(Vec3(0, 0, 0), Vec3(16, 0, 0), Vec3(0, 16, 0), 1, 2), 8);
  flat.addSphere(Sphere{Vec3(1.5f, 0, 0.5f), 0.3f}, 5);
  flat.build();
  ASSERT_FALSE(flat.usesEmbree());
  EXPECT_EQ(intersectManyMismatches(flat, cameraFans(rng, Vec3(8, 8, 20), 16.f, 16, 3000)).any, 0);
}

// Where two surfaces overlap in one plane (coplanar triangles of two meshes: z-fighting), a ray meets
// both within an ulp or two of one distance, and which one Embree reports depends on its traversal
// (the order, and its boxes' rounding), which differs in a stream: the hits then differ in the
// surface, by at most 4 ulps in the distance, never otherwise.
TEST(SceneGeometry, IntersectManyDiffersOnlyBetweenSurfacesAtTheSameDistance) {
  std::mt19937 rng(13);
  SceneGeometry g;
  g.addMesh(makeGridPlane(Vec3(0, 0, 0), Vec3(16, 0, 0), Vec3(0, 16, 0), 16, 16), 8);
  g.addMesh(makeGridPlane(Vec3(0, 0, 0), Vec3(16, 0, 0), Vec3(0, 16, 0), 7, 5), 9);
  g.build(AccelMode::Embree);
  for (const Vec3& eye : {Vec3(8, 8, 20), Vec3(-3, 5, 4)}) {
    const Mismatches m = intersectManyMismatches(g, cameraFans(rng, eye, 16.f, 16, 3000));
    EXPECT_EQ(m.any, m.tiesAtTheSameDistance);
  }
}

// Concurrent const queries give the same answers as serial ones.
TEST(SceneGeometry, ConcurrentQueriesMatchSerial) {
  SceneGeometry g = rockScene(AccelMode::Auto, 4);
  ASSERT_TRUE(g.usesEmbree());
  std::mt19937 rng(9);
  std::vector<Ray> rays(20000);
  for (Ray& r : rays) {
    r.o = randomUnit(rng) * 4.f;
    r.d = glm::normalize(randomUnit(rng) * 0.5f - r.o);
  }
  std::vector<float> serial(rays.size()), parallel(rays.size());
  std::vector<char> occSerial(rays.size()), occParallel(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    SurfaceHit h;
    serial[i] = g.intersect(rays[i], h) ? h.t : -1.f;
    occSerial[i] = g.occluded(rays[i]);
  }
  auto work = [&](size_t begin) {
    for (size_t i = begin; i < rays.size(); i += 2) {
      SurfaceHit h;
      parallel[i] = g.intersect(rays[i], h) ? h.t : -1.f;
      occParallel[i] = g.occluded(rays[i]);
    }
  };
  std::thread a(work, 0), b(work, 1);
  a.join();
  b.join();
  EXPECT_EQ(serial, parallel);
  EXPECT_EQ(occSerial, occParallel);
}

// End-to-end check of offsets and occlusion against a closed form (closed-forms.md): a point on a
// plane at horizontal distance ρ from the contact point of a sphere of radius R resting on it has
// AO = 1 − R³/(ρ² + R²)^{3/2}. Cosine-weighted directions (local Malley warp) make AO = E[V]; the
// estimate must be within 4 binomial standard errors at every scale (self-hits would bias it down).
TEST(SceneGeometry, AmbientOcclusionOfSphereOnPlaneMatchesClosedForm) {
  for (auto [mode, sphereMode] : kAccelCombinations) {
    for (float k : {1e-4f, 1.f, 1e4f}) {
      const float R = 0.5f * k;
      SceneGeometry g;
      g.addMesh(makeGridPlane(Vec3(-100 * k, -100 * k, 0), Vec3(200 * k, 0, 0), Vec3(0, 200 * k, 0), 1, 1),
                0);
      g.addSphere(Sphere{Vec3(0.3f * k, -0.2f * k, R), R}, 1);
      g.build(mode, sphereMode);
      for (float rhoOverR : {0.3f, 1.f, 2.5f}) {
        // Find the shading point by casting a ray at the plane from below (the sphere is above), so it
        // carries real rounding; ng is +z by winding whichever side the ray came from.
        const Vec3 target(0.3f * k + rhoOverR * R, -0.2f * k, 0.f);
        SurfaceHit hit;
        ASSERT_TRUE(g.intersect(
            Ray{target - Vec3(0.1f * k, 0.f, 3.f * k), glm::normalize(Vec3(0.1f, 0.f, 3.f))}, hit));
        ASSERT_EQ(hit.ng, Vec3(0, 0, 1));
        ASSERT_EQ(hit.objectId, 0u);
        const double rho = glm::length(DVec3(hit.p) - DVec3(0.3f * k, -0.2f * k, 0.0));
        const double truth = 1.0 - std::pow(double(R), 3) / std::pow(rho * rho + double(R) * R, 1.5);
        std::mt19937 rng(10);
        std::uniform_real_distribution<float> u(0.f, 1.f);
        const int n = 40000;
        int visible = 0;
        for (int i = 0; i < n; ++i) {
          const float r = std::sqrt(u(rng)), phi = 2.f * kPi * u(rng);
          const Vec3 w(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.f, 1.f - r * r)));
          Ray ao{offsetRayOrigin(hit.p, hit.ng, hit.offsetScale, w), w, 0.f, 10.f * g.bounds().diagonal()};
          visible += !g.occluded(ao);
        }
        const double est = double(visible) / n;
        const double se = std::sqrt(truth * (1 - truth) / n);
        EXPECT_NEAR(est, truth, 4 * se) << "k=" << k << " rho/R=" << rhoOverR;
      }
    }
  }
}

TEST(ProceduralMesh, RockIsDeterministicAndSized) {
  TriangleMesh a = makeRockMesh(3, 9), b = makeRockMesh(3, 9), c = makeRockMesh(3, 10);
  EXPECT_EQ(a.triangles.size(), 20u * 64u);
  EXPECT_EQ(a.positions.size(), a.normals.size());
  EXPECT_EQ(a.positions.size(), 10u * 64u + 2u);  // closed icosphere: V = 10·4^s + 2
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_NE(a.positions, c.positions);
  for (const Vec3& p : a.positions) {
    EXPECT_GT(glm::length(p), 0.4f);
    EXPECT_LT(glm::length(p), 1.5f);
  }
  for (const Vec3& n : a.normals) EXPECT_NEAR(glm::length(n), 1.f, 1e-5f);
}

}  // namespace
}  // namespace penumbra
