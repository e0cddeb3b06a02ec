#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/lights/polygon_light.h"
#include "core/lights/projected_polygon.h"
#include "core/render/packet_kernels.h"
#include "core/render/packet_scene.h"
#include "core/render/packet_target_test_support.h"
#include "core/sampling/rng.h"

namespace penumbra {
namespace {

using test::ForcedTarget;

// A polygon light and a shading point (x, normal n) that sees it.
struct Setting {
  PolygonLight light;
  Vec3 x, n;
};

Vec3 randomUnit(Rng& rng) {
  for (;;) {
    const Vec3 v(2 * rng.nextFloat() - 1, 2 * rng.nextFloat() - 1, 2 * rng.nextFloat() - 1);
    const float len2 = glm::dot(v, v);
    if (len2 > 1e-4f && len2 <= 1.f) return v / std::sqrt(len2);
  }
}

// The light on p0, e1, e2 wound to emit towards x (its normal faces x).
PolygonLight facing(const Vec3& p0, Vec3 e1, Vec3 e2, bool parallelogram, const Vec3& x) {
  if (glm::dot(glm::cross(e1, e2), x - p0) < 0.f) std::swap(e1, e2);
  return PolygonLight::make(p0, e1, e2, parallelogram, Color3(1.f));
}

// Settings of every shape the map meets: a horizontal light over a tilted receiver (the zenith inside
// the polygon or outside it), lights large and near (wedges wider than 3π/4, halved), small and far,
// sheared parallelograms, random ones reaching below the horizon, at scales 1e-4 to 1e4 away from the
// origin; and ones with nothing to sample (behind the light, in its plane, a degenerate light).
std::vector<Setting> settings(Rng& rng) {
  std::vector<Setting> out;
  for (int i = 0; i < 3000; ++i) {
    const bool parallelogram = rng.nextU32() % 2 == 0;
    const int kind = int(rng.nextU32() % 5);
    const float scale = std::array<float, 3>{1e-4f, 1.f, 1e4f}[rng.nextU32() % 3];
    const Vec3 offset = scale * Vec3(10 * rng.nextFloat(), -5 * rng.nextFloat(), 3 * rng.nextFloat());
    Vec3 x(0.f), n(0.f, 1.f, 0.f), p0, e1, e2;
    if (kind == 0 || kind == 1) {
      // A light at height 1 (overhead) or 0.05 (large and near) over a receiver tilted up to 24°, the
      // point below it about half the time.
      const float height = kind == 0 ? 1.f : 0.05f, size = kind == 0 ? 1.f : 4.f;
      e1 = Vec3(size * (0.2f + rng.nextFloat()), 0.f, 0.3f * size * (rng.nextFloat() - 0.5f));
      e2 = Vec3(0.3f * size * (rng.nextFloat() - 0.5f), 0.f, size * (0.2f + rng.nextFloat()));
      p0 = Vec3(0.f, height, 0.f) - (1.4f * rng.nextFloat() - 0.2f) * e1 -
           (1.4f * rng.nextFloat() - 0.2f) * e2;
      n = glm::normalize(Vec3(0.f, 1.f, 0.f) + 0.4f * randomUnit(rng) * rng.nextFloat());
    } else if (kind == 2) {
      // Small and far: 1e-5 across at distance 1 to 100.
      const Vec3 towards = randomUnit(rng);
      p0 = towards * (1.f + 99.f * rng.nextFloat());
      e1 = 1e-5f * randomUnit(rng);
      e2 = 1e-5f * randomUnit(rng);
      n = glm::normalize(towards + 0.5f * randomUnit(rng));
    } else {
      // Anywhere near x, seen from any normal (many reach below the horizon).
      p0 = 2.f * randomUnit(rng);
      e1 = randomUnit(rng) * (0.1f + rng.nextFloat());
      e2 = randomUnit(rng) * (0.1f + rng.nextFloat());
      n = randomUnit(rng);
    }
    x = x * scale + offset;
    p0 = p0 * scale + offset;
    out.push_back({facing(p0, e1 * scale, e2 * scale, parallelogram, x), x, n});
  }
  const Vec3 p0(0.f, 1.f, 0.f), e1(1.f, 0.f, 0.f), e2(0.f, 0.f, 1.f);
  const Vec3 up(0.f, 1.f, 0.f);
  out.push_back({facing(p0, e1, e2, true, Vec3(0.f)), Vec3(0.5f, 2.f, 0.5f), up});     // behind it
  out.push_back({facing(p0, e1, e2, true, Vec3(0.f)), Vec3(3.f, 1.f, 0.5f), up});      // in its plane
  out.push_back({PolygonLight::make(p0, e1, e1, false, Color3(1.f)), Vec3(0.f), up});  // degenerate
  return out;
}

// What LightTechnique<ProjectedSolidAngle, PolygonLight> sets up for `s`: false where it samples nothing.
bool scalarMap(const Setting& s, ProjectedPolygon& map) {
  if (!s.light.valid() || !s.light.faces(s.x)) return false;
  Vec3 v[4];
  s.light.vertices(v);
  return map.init(v, s.light.vertexCount(), s.x, s.n) && float(map.projectedSolidAngle) > 0.f;
}

// The lowest vertex's height over x's horizon.
double lowestVertex(const Setting& s) {
  Vec3 v[4];
  s.light.vertices(v);
  const DVec3 n = glm::normalize(DVec3(s.n));
  double lowest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < s.light.vertexCount(); ++i)
    lowest = std::min(lowest, glm::dot(DVec3(v[i]) - DVec3(s.x), n));
  return lowest;
}

// The projected solid angle's map of polygon lights in lanes sets up and samples what ProjectedPolygon
// does, bit for bit (its Ω⊥ and every direction), on every instruction set: lanes with the zenith
// inside the polygon and outside it, wedges halved, triangles and parallelograms side by side, draws at
// 0 and 1⁻; a polygon reaching below the horizon is left to the scalar technique, and nothing is
// sampled where the scalar technique samples nothing.
TEST(PacketProjectedPolygon, MapsWhatTheScalarMapMaps) {
  Rng settingRng(3, 7);
  const std::vector<Setting> all = settings(settingRng);
  const float belowOne = std::nextafter(1.f, 0.f);
  for (const std::string& target : availablePacketTargets()) {
    ForcedTarget forced(target);
    const int lanes = std::min(packetLanes(), kMaxPacketLanes);
    Rng rng(5, 1);
    int inLanes = 0, byScalar = 0, none = 0, zenithInside = 0, zenithOutside = 0, halved = 0;
    for (size_t first = 0; first < all.size(); first += size_t(lanes)) {
      std::vector<PacketPolygonLight> polygons;
      float x[3][kMaxPacketLanes] = {}, n[3][kMaxPacketLanes] = {}, active[kMaxPacketLanes] = {};
      for (int k = 0; k < lanes; ++k) {
        const Setting& s = all[std::min(first + size_t(k), all.size() - 1)];
        polygons.push_back(packetPolygonLight(s.light));
        for (int c = 0; c < 3; ++c) x[c][k] = s.x[c], n[c][k] = s.n[c];
        active[k] = first + size_t(k) < all.size() && (first + size_t(k)) % 7 != 6 ? 1.f : 0.f;
      }
      for (int draw = 0; draw < 6; ++draw) {
        float u[2][kMaxPacketLanes];
        for (int k = 0; k < lanes; ++k) {
          u[0][k] = draw == 0 ? 0.f : draw == 1 ? belowOne : rng.nextFloat();
          u[1][k] = draw == 0 ? belowOne : draw == 1 ? 0.f : rng.nextFloat();
        }
        double w[3][kMaxPacketLanes], projected[kMaxPacketLanes];
        float mapped[kMaxPacketLanes];
        packetKernels().projectedPolygons(polygons, x, n, active, u, w, projected, mapped);
        for (int k = 0; k < lanes; ++k) {
          const size_t index = first + size_t(k);
          SCOPED_TRACE(target + " setting " + std::to_string(index) + " draw " + std::to_string(draw));
          if (active[k] == 0.f) {
            ASSERT_EQ(mapped[k], 0.f);
            continue;
          }
          const Setting& s = all[index];
          ProjectedPolygon map;
          const bool valid = scalarMap(s, map);
          if (mapped[k] == 1.f) {
            ASSERT_TRUE(valid);
            ASSERT_EQ(projected[k], map.projectedSolidAngle);
            const DVec3 expected = map.sampleDirection(Vec2(u[0][k], u[1][k]));
            ASSERT_EQ(w[0][k], expected.x);
            ASSERT_EQ(w[1][k], expected.y);
            ASSERT_EQ(w[2][k], expected.z);
            if (draw > 0) continue;
            ++inLanes;
            const bool inside = !map.wedges[0].hasInner;
            ++(inside ? zenithInside : zenithOutside);
            const int vertices = s.light.vertexCount();
            if (map.wedgeCount > (inside ? vertices : vertices - 1)) ++halved;
          } else if (mapped[k] == 2.f) {
            ASSERT_TRUE(s.light.valid() && s.light.faces(s.x));
            ASSERT_FALSE(lowestVertex(s) > 0.0);
            if (draw == 0) ++byScalar;
          } else {
            ASSERT_EQ(mapped[k], 0.f);
            ASSERT_FALSE(valid);
            if (draw == 0) ++none;
          }
        }
      }
    }
    SCOPED_TRACE(target);
    EXPECT_GT(zenithInside, 100);
    EXPECT_GT(zenithOutside, 500);
    EXPECT_GT(halved, 50);
    EXPECT_GT(byScalar, 300);
    EXPECT_GE(none, 3);
    EXPECT_GT(inLanes, 1000);
  }
}

}  // namespace
}  // namespace penumbra
