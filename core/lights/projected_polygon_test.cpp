#include "core/lights/projected_polygon.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "core/lights/polygon_lambert.h"
#include "core/sampling/chi2.h"

namespace penumbra {
namespace {

const Vec3 kUp(0.f, 0.f, 1.f);

// A polygon light seen from x (normal n).
struct Config {
  const char* name;
  std::vector<Vec3> vertices;
  Vec3 x{0.f}, n{0.f, 0.f, 1.f};
  bool solidAnglePdfDetectable = true;  // cos θ varies over it enough for 10⁶ samples to see
  // χ² bins on the polygon itself (its parallelogram's coordinates), else on the projection disk (for a
  // polygon so large that its density crowds into a small part of it).
  bool binOnThePolygon = true;
};

std::vector<Vec3> square(Vec3 centre, Vec3 u, Vec3 v) {
  return {centre - u - v, centre + u - v, centre + u + v, centre - u + v};
}

std::vector<Vec3> scaled(std::vector<Vec3> p, float s, Vec3 offset) {
  for (Vec3& q : p) q = q * s + offset;
  return p;
}

// Each the way a floor point sees a ceiling light, a wall, a window: above the horizon with the normal's
// direction inside or outside it, straddling, grazing, tiny, sliver, huge; and the same at 1e-3 and 1e3.
std::vector<Config> configs() {
  const std::vector<Vec3> overhead = square(Vec3(0.1f, -0.05f, 1.f), Vec3(0.4f, 0, 0), Vec3(0, 0.3f, 0));
  std::vector<Config> c = {
      {"overheadQuad", overhead},
      {"offsetTriangle", {Vec3(0.8f, 0.2f, 1.f), Vec3(1.6f, 0.1f, 1.2f), Vec3(1.1f, 0.9f, 0.9f)}},
      {"triangleOverNormal", {Vec3(-0.5f, -0.4f, 0.7f), Vec3(0.6f, -0.3f, 0.9f), Vec3(0.f, 0.7f, 0.8f)}},
      {"straddlingWall", square(Vec3(1.f, 0.2f, 0.1f), Vec3(0, 0.5f, 0), Vec3(0, 0, 0.5f))},
      {"straddlingTiltedOverNormal",
       square(Vec3(0.2f, 0.1f, 0.3f), Vec3(2.f, 0.f, 0.6f), Vec3(0.f, 1.5f, -0.4f))},
      {"straddlingTriangle", {Vec3(0.5f, -0.5f, -0.3f), Vec3(0.7f, 0.6f, 0.4f), Vec3(1.2f, 0.f, 0.6f)}},
      {"grazingWindow", square(Vec3(3.f, 0.f, 0.0105f), Vec3(0, 1.f, 0), Vec3(0, 0, 0.0095f)), Vec3(0.f), kUp,
       false},
      {"lightCentreOnHorizon", square(Vec3(2.f, 0.f, 0.f), Vec3(0, 0.7f, 0), Vec3(0.3f, 0, 0.6f))},
      {"tiny1e-6",
       {Vec3(0.6f, 0.3f, 0.7f), Vec3(0.6f + 1e-6f, 0.3f, 0.7f), Vec3(0.6f, 0.3f + 1e-6f, 0.7f)},
       Vec3(0.f),
       kUp,
       false},
      {"tinyOverNormal1e-6", square(Vec3(0, 0, 1), Vec3(1e-6f, 0, 0), Vec3(0, 1e-6f, 0)), Vec3(0.f), kUp,
       false},
      {"sliver1e4", {Vec3(-1.f, 0.2f, 1.f), Vec3(1.f, 0.2f, 1.f), Vec3(0.f, 0.2002f, 1.f)}},
      // Binned on the disk, where 1 / cos θ (the solid-angle density) has no finite integral to compare with.
      {"hugeNearlyAHemisphere", square(Vec3(0, 0, 0.01f), Vec3(100.f, 0, 0), Vec3(0, 100.f, 0)), Vec3(0.f),
       kUp, false, false},
      {"tiltedNormal", overhead, Vec3(0.2f, 0.1f, 0.f), glm::normalize(Vec3(0.6f, -0.3f, 0.7f))},
  };
  // The same scenes at 1e-3 and 1e3, far from the origin.
  for (float s : {1e-3f, 1e3f}) {
    const Vec3 offset = Vec3(3.f, -2.f, 5.f) * s;
    c.push_back({s < 1 ? "overheadQuad1e-3" : "overheadQuad1e3", scaled(overhead, s, offset), offset});
    c.push_back({s < 1 ? "straddlingWall1e-3" : "straddlingWall1e3",
                 scaled(square(Vec3(1.f, 0.2f, 0.1f), Vec3(0, 0.5f, 0), Vec3(0, 0, 0.5f)), s, offset),
                 offset});
  }
  return c;
}

std::vector<glm::dvec3> toDouble(const std::vector<Vec3>& v) {
  return std::vector<glm::dvec3>(v.begin(), v.end());
}

// Whether the ray from x along w meets the polygon (convex, either winding): an inside test of its own,
// independent of the map's edge normals.
bool rayMeetsPolygon(const Config& c, const DVec3& w) {
  const DVec3 x(c.x), v0(c.vertices[0]);
  const DVec3 nl = glm::cross(DVec3(c.vertices[1]) - v0, DVec3(c.vertices[2]) - v0);
  const double denom = glm::dot(nl, w);
  if (denom == 0) return false;
  const double t = glm::dot(nl, v0 - x) / denom;
  if (!(t > 0)) return false;
  const DVec3 p = x + w * t;
  int positive = 0, negative = 0;
  const size_t k = c.vertices.size();
  for (size_t i = 0; i < k; ++i) {
    const DVec3 a(c.vertices[i]), b(c.vertices[(i + 1) % k]);
    const double s = glm::dot(glm::cross(b - a, p - a), nl);
    (s >= 0 ? positive : negative)++;
  }
  return positive == 0 || negative == 0;
}

// The polygon's projection onto x's tangent disk, in a box that holds it (its boundary traced in 3-D,
// clipped to the horizon, projected), mapped onto [0,1]²: the χ² test's own coordinates.
struct DiskBox {
  DVec3 ex, ey, ez;
  double x0 = 1, x1 = -1, y0 = 1, y1 = -1;

  explicit DiskBox(const Config& c) {
    ez = glm::normalize(DVec3(c.n));
    ex = glm::normalize(glm::cross(std::fabs(ez.x) < 0.9 ? DVec3(1, 0, 0) : DVec3(0, 1, 0), ez));
    ey = glm::cross(ez, ex);
    const size_t k = c.vertices.size();
    for (size_t i = 0; i < k; ++i)
      for (int j = 0; j <= 4096; ++j) {
        const DVec3 a(c.vertices[i]), b(c.vertices[(i + 1) % k]);
        const DVec3 d = glm::normalize(a + (b - a) * (j / 4096.0) - DVec3(c.x));
        DVec3 l(glm::dot(d, ex), glm::dot(d, ey), glm::dot(d, ez));
        if (l.z < 0) {  // below the horizon: its projection onto the unit circle bounds the clipped part
          const double len = std::hypot(l.x, l.y);
          l = DVec3(l.x / len, l.y / len, 0);
        }
        x0 = std::min(x0, l.x), x1 = std::max(x1, l.x), y0 = std::min(y0, l.y), y1 = std::max(y1, l.y);
      }
    const double mx = 1e-3 * (x1 - x0), my = 1e-3 * (y1 - y0);  // the ellipse arcs between the traced points
    x0 = std::max(-1.0, x0 - mx), x1 = std::min(1.0, x1 + mx), y0 = std::max(-1.0, y0 - my),
    y1 = std::min(1.0, y1 + my);
  }
  Vec3 toSquare(const DVec3& w) const {
    const double s = (glm::dot(w, ex) - x0) / (x1 - x0), t = (glm::dot(w, ey) - y0) / (y1 - y0);
    return Vec3(float(std::clamp(s, 0.0, double(kOneMinusEpsilon))),
                float(std::clamp(t, 0.0, double(kOneMinusEpsilon))), 0.f);
  }
  // The direction above the horizon at a point of the square (false: outside the unit disk).
  bool fromSquare(double s, double t, DVec3& w) const {
    const double px = x0 + s * (x1 - x0), py = y0 + t * (y1 - y0), z2 = 1 - px * px - py * py;
    if (!(z2 > 0)) return false;
    w = ex * px + ey * py + ez * std::sqrt(z2);
    return true;
  }
  double area() const { return (x1 - x0) * (y1 - y0); }
};

// The polygon's own coordinates: p = v0 + s a + t b over the parallelogram of its first edges (a
// triangle is its half s + t ≤ 1), onto [0,1]², with the density of directions carried over to them.
struct PlaneBox {
  DVec3 x, v0, a, b, nl, n;
  double jacobian;
  bool triangle;

  explicit PlaneBox(const Config& c)
      : x(c.x),
        v0(c.vertices[0]),
        a(DVec3(c.vertices[1]) - v0),
        b(DVec3(c.vertices.back()) - v0),
        nl(glm::normalize(glm::cross(a, b))),
        n(glm::normalize(DVec3(c.n))),
        jacobian(glm::length(glm::cross(a, b))),
        triangle(c.vertices.size() == 3) {}
  Vec3 toSquare(const DVec3& w) const {
    const double t = glm::dot(nl, v0 - x) / glm::dot(nl, w);
    const DVec3 q = x + w * t - v0;
    // Solve q = s a + t b (q lies in the plane).
    const double aa = glm::dot(a, a), ab = glm::dot(a, b), bb = glm::dot(b, b), qa = glm::dot(q, a),
                 qb = glm::dot(q, b), det = aa * bb - ab * ab;
    const double s = (qa * bb - qb * ab) / det, u = (qb * aa - qa * ab) / det;
    return Vec3(float(std::clamp(s, 0.0, double(kOneMinusEpsilon))),
                float(std::clamp(u, 0.0, double(kOneMinusEpsilon))), 0.f);
  }
  // The direction towards the point at (s, t), and the factor from a direction density to one over
  // [0,1]²: |cos θ_L| |a × b| / d². False outside the polygon or below the horizon.
  bool fromSquare(double s, double t, DVec3& w, double& factor) const {
    if (triangle && s + t > 1) return false;
    const DVec3 d = v0 + a * s + b * t - x;
    const double d2 = glm::dot(d, d);
    w = d / std::sqrt(d2);
    if (!(glm::dot(w, n) > 0)) return false;
    factor = std::fabs(glm::dot(nl, w)) * jacobian / d2;
    return true;
  }
};

// Lambert's Ω⊥ of the polygon whichever way it is wound (the map does not care which side emits).
double lambert(const Config& c) {
  std::vector<glm::dvec3> v = toDouble(c.vertices);
  const double front = polygonLightIrradianceFactor(DVec3(c.x), DVec3(c.n), v);
  std::reverse(v.begin(), v.end());
  return std::max(front, polygonLightIrradianceFactor(DVec3(c.x), DVec3(c.n), v));
}

enum class Judge { Map, SolidAngle, WrongRadius };

Chi2Result polygonChi2(const Config& c, const ProjectedPolygon& map, Judge judge, int testCount) {
  const DiskBox disk(c);
  const PlaneBox plane(c);
  const DVec3 n = glm::normalize(DVec3(c.n));
  Chi2Options o;
  o.sampleCount = judge == Judge::Map ? 1'000'000 : 200'000;  // the wrong densities are far off
  o.resolution = 40;
  o.seed = 11;
  o.testCount = testCount;
  auto sample = [&](Vec2 u) {
    if (judge == Judge::WrongRadius) u.y = u.y * u.y;  // r² no longer uniform: must be rejected
    const DVec3 w = map.sampleDirection(u);
    return c.binOnThePolygon ? plane.toSquare(w) : disk.toSquare(w);
  };
  // A direction density over the square's coordinates.
  auto overSquare = [&](const Vec3& p, auto directionDensity) -> double {
    DVec3 w;
    if (c.binOnThePolygon) {
      double factor;
      return plane.fromSquare(p.x, p.y, w, factor) ? directionDensity(w) * factor : 0.0;
    }
    // Over dx dy of the disk: a direction density / cos θ.
    return disk.fromSquare(p.x, p.y, w) && rayMeetsPolygon(c, w)
               ? directionDensity(w) / glm::dot(w, n) * disk.area()
               : 0.0;
  };
  const double projectedSolidAngle = lambert(c);
  // The uniform solid-angle density (the wrong one) needs the clipped polygon's solid angle.
  double solidAngle = 0;
  if (judge == Judge::SolidAngle)
    solidAngle = integratePdf(
        Chi2Domain::square(0.0, 1.0),
        [&](const Vec3& p) { return overSquare(p, [](const DVec3&) { return 1.0; }); }, 40);
  auto pdf = [&](const Vec3& p) -> double {
    if (judge == Judge::SolidAngle) return overSquare(p, [&](const DVec3&) { return 1.0 / solidAngle; });
    return overSquare(p, [&](const DVec3& w) { return glm::dot(w, n) / projectedSolidAngle; });
  };
  return chi2Test(Chi2Domain::square(0.0, 1.0), sample, pdf, o);
}

TEST(ProjectedPolygon, ProjectedSolidAngleIsLambertsClosedForm) {
  for (const Config& c : configs()) {
    ProjectedPolygon map;
    ASSERT_TRUE(map.init(c.vertices.data(), int(c.vertices.size()), c.x, c.n)) << c.name;
    const double expected = lambert(c);
    EXPECT_NEAR(map.projectedSolidAngle / expected, 1.0, 1e-9)
        << c.name << ": " << map.projectedSolidAngle << " against " << expected;
  }
}

TEST(ProjectedPolygon, Chi2OnThePolygon) {
  const std::vector<Config> all = configs();
  for (const Config& c : all) {
    ProjectedPolygon map;
    ASSERT_TRUE(map.init(c.vertices.data(), int(c.vertices.size()), c.x, c.n)) << c.name;
    const Chi2Result r = polygonChi2(c, map, Judge::Map, int(all.size()));
    if (std::getenv("PENUMBRA_VERBOSE"))
      std::printf("%-28s wedges %d chi2 %9.2f dof %5d p %.4f %s\n", c.name, map.wedgeCount, r.chi2, r.dof,
                  r.pValue, r.accepted ? "accept" : "reject");
    EXPECT_TRUE(r.accepted) << c.name << ": " << r.message << " p = " << r.pValue;
  }
}

// The test of the test: the uniform solid-angle density, and a map whose r² is not uniform, are
// rejected.
TEST(ProjectedPolygon, Chi2RejectsTheSolidAnglePdfAndAWrongRadius) {
  const std::vector<Config> all = configs();
  for (const Config& c : all) {
    ProjectedPolygon map;
    ASSERT_TRUE(map.init(c.vertices.data(), int(c.vertices.size()), c.x, c.n)) << c.name;
    if (c.solidAnglePdfDetectable) {
      EXPECT_FALSE(polygonChi2(c, map, Judge::SolidAngle, int(all.size())).accepted)
          << c.name << " solid angle";
    }
    EXPECT_FALSE(polygonChi2(c, map, Judge::WrongRadius, int(all.size())).accepted)
        << c.name << " wrong radius";
  }
}

// The map's pdf integrates to 1 over the polygon (in its own coordinates, or the disk's for the huge
// one), and is positive exactly where the ray meets the polygon.
TEST(ProjectedPolygon, PdfIntegratesToOneWhereTheRayMeetsThePolygon) {
  for (const Config& c : configs()) {
    ProjectedPolygon map;
    ASSERT_TRUE(map.init(c.vertices.data(), int(c.vertices.size()), c.x, c.n)) << c.name;
    const DiskBox disk(c);
    const PlaneBox plane(c);
    const DVec3 n = glm::normalize(DVec3(c.n));
    int disagreements = 0, probes = 0;
    const double integral = integratePdf(
        Chi2Domain::square(0.0, 1.0),
        [&](const Vec3& p) {
          DVec3 w;
          double factor = 0;
          if (c.binOnThePolygon ? !plane.fromSquare(p.x, p.y, w, factor) : !disk.fromSquare(p.x, p.y, w))
            return 0.0;
          if (!c.binOnThePolygon) factor = disk.area() / glm::dot(w, n);
          const double pdf = map.pdfDirection(w);
          // The quadrature's nodes include the polygon's edges (s, t = 0 or 1, s + t = 1): leave them out.
          const double m = 1e-9;
          const bool onEdge = c.binOnThePolygon && (p.x < m || p.y < m || p.x > 1 - m || p.y > 1 - m ||
                                                    (plane.triangle && p.x + p.y > 1 - m));
          if (!onEdge) {
            ++probes;
            if ((pdf > 0) != (glm::dot(w, n) > 0 && rayMeetsPolygon(c, w))) ++disagreements;
          }
          return pdf * factor;
        },
        40);
    EXPECT_NEAR(integral, 1.0, 1e-6) << c.name;
    EXPECT_LE(disagreements, probes / 100000) << c.name << " (on the boundary, within rounding)";
  }
}

// Every sample is a finite unit direction above the horizon that meets the polygon, with its density.
TEST(ProjectedPolygon, SamplesAreInsideWithTheirDensity) {
  for (const Config& c : configs()) {
    ProjectedPolygon map;
    ASSERT_TRUE(map.init(c.vertices.data(), int(c.vertices.size()), c.x, c.n)) << c.name;
    int missed = 0;
    for (int i = 0; i <= 64; ++i)
      for (int j = 0; j <= 64; ++j) {
        const Vec2 u(std::min(i / 64.f, kOneMinusEpsilon), std::min(j / 64.f, kOneMinusEpsilon));
        const DVec3 w = map.sampleDirection(u);
        ASSERT_TRUE(std::isfinite(w.x) && std::isfinite(w.y) && std::isfinite(w.z)) << c.name;
        EXPECT_NEAR(glm::length(w), 1.0, 1e-12) << c.name;
        EXPECT_GE(glm::dot(w, glm::normalize(DVec3(c.n))), 0.0) << c.name;
        const bool interior = i > 0 && i < 64 && j > 0 && j < 64;
        if (interior && (map.pdfDirection(w) <= 0 || !rayMeetsPolygon(c, w))) ++missed;
      }
    EXPECT_EQ(missed, 0) << c.name;
  }
}

// The map keeps stratification: the area below the sampled azimuth grows with u.x, r² with u.y.
TEST(ProjectedPolygon, MapIsMonotoneInBothCoordinates) {
  for (const Config& c : configs()) {
    ProjectedPolygon map;
    ASSERT_TRUE(map.init(c.vertices.data(), int(c.vertices.size()), c.x, c.n)) << c.name;
    const DVec3 ez = glm::normalize(DVec3(c.n));
    for (float v : {0.1f, 0.5f, 0.9f}) {
      double lastR2 = -1;
      for (int j = 0; j <= 256; ++j) {
        const DVec3 w = map.sampleDirection(Vec2(v, std::min(j / 256.f, kOneMinusEpsilon)));
        const double r2 = 1 - glm::dot(w, ez) * glm::dot(w, ez);
        EXPECT_GE(r2, lastR2 - 1e-12) << c.name << " u.y " << j / 256.0;
        lastR2 = r2;
      }
    }
    // Along u.x, the direction turns one way about the normal (counter-clockwise in the map's frame).
    DVec3 last = map.sampleDirection(Vec2(0.f, 0.5f));
    double turned = 0;
    for (int i = 1; i <= 512; ++i) {
      const DVec3 w = map.sampleDirection(Vec2(std::min(i / 512.f, kOneMinusEpsilon), 0.5f));
      const double step = std::atan2(glm::dot(glm::cross(last, w), ez),
                                     glm::dot(last - ez * glm::dot(last, ez), w - ez * glm::dot(w, ez)));
      EXPECT_GE(step, -1e-9) << c.name << " u.x " << i / 512.0;
      turned += step;
      last = w;
    }
    EXPECT_LE(turned, 2 * kPiD + 1e-6) << c.name;
  }
}

TEST(ProjectedPolygon, NothingToSample) {
  ProjectedPolygon map;
  const std::vector<Vec3> quad = square(Vec3(0, 0, 1), Vec3(0.5f, 0, 0), Vec3(0, 0.5f, 0));
  EXPECT_FALSE(map.init(quad.data(), 4, Vec3(0.2f, 0.1f, 1.f), Vec3(0, 0, 1)));  // in its plane
  EXPECT_FALSE(map.init(quad.data(), 4, Vec3(0), Vec3(0, 0, -1)));               // below the horizon
  EXPECT_EQ(map.projectedSolidAngle, 0.0);
  const Vec3 line[3] = {Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(2, 0, 1)};  // no area
  EXPECT_FALSE(map.init(line, 3, Vec3(0), Vec3(0, 0, 1)));
  const Vec3 nan[3] = {Vec3(0, 0, 1), Vec3(NAN, 0, 1), Vec3(0, 1, 1)};
  EXPECT_FALSE(map.init(nan, 3, Vec3(0), Vec3(0, 0, 1)));
  // Wound either way, the same map.
  std::vector<Vec3> reversed(quad.rbegin(), quad.rend());
  ProjectedPolygon a, b;
  ASSERT_TRUE(a.init(quad.data(), 4, Vec3(0.1f, 0, 0), Vec3(0, 0, 1)));
  ASSERT_TRUE(b.init(reversed.data(), 4, Vec3(0.1f, 0, 0), Vec3(0, 0, 1)));
  EXPECT_NEAR(a.projectedSolidAngle, b.projectedSolidAngle, 1e-15);
}

}  // namespace
}  // namespace penumbra
