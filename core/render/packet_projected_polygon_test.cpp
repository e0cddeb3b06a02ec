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
#include "core/render/packet_polygon_settings_test_support.h"
#include "core/render/packet_scene.h"
#include "core/render/packet_target_test_support.h"
#include "core/sampling/rng.h"

namespace penumbra {
namespace {

using test::ForcedTarget;
using test::Setting;

// What LightTechnique<ProjectedSolidAngle, PolygonLight> sets up for `s`: false where it samples nothing.
bool scalarMap(const Setting& s, ProjectedPolygon& map) {
  if (!s.light.valid() || !s.light.faces(s.x)) return false;
  Vec3 v[4];
  s.light.vertices(v);
  return map.init(v, s.light.vertexCount(), s.x, s.n) && float(map.projectedSolidAngle) > 0.f;
}

// The projected solid angle's map of polygon lights in lanes sets up and samples what ProjectedPolygon
// does, bit for bit (its Ω⊥ and every direction), on every instruction set: lanes with the zenith
// inside the polygon and outside it, wedges halved, triangles and parallelograms side by side, polygons
// reaching below the horizon (clipped to three, four or five vertices), draws at 0 and 1⁻; nothing is
// sampled where the scalar technique samples nothing.
TEST(PacketProjectedPolygon, MapsWhatTheScalarMapMaps) {
  Rng settingRng(3, 7);
  const std::vector<Setting> all = test::polygonSettings(settingRng);
  const float belowOne = std::nextafter(1.f, 0.f);
  for (const std::string& target : availablePacketTargets()) {
    ForcedTarget forced(target);
    const int lanes = std::min(packetLanes(), kMaxPacketLanes);
    Rng rng(5, 1);
    int inLanes = 0, none = 0, zenithInside = 0, zenithOutside = 0, halved = 0;
    std::array<int, ProjectedPolygon::kMaxVertices + 1> clippedTo{};
    for (size_t first = 0; first < all.size(); first += size_t(lanes)) {
      const test::SettingLanes packet = test::settingLanes(all, first, lanes);
      const auto& polygons = packet.polygons;
      const auto &x = packet.x, &n = packet.n;
      const auto& active = packet.active;
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
            const int vertices = map.edgeCount;
            if (map.wedgeCount > (inside ? vertices : vertices - 1)) ++halved;
            if (!(test::lowestVertexHeight(s) > 0.0)) ++clippedTo[size_t(vertices)];
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
    EXPECT_GT(clippedTo[3], 100);  // a triangle or parallelogram cut down to a triangle
    EXPECT_GT(clippedTo[4], 100);
    EXPECT_GT(clippedTo[5], 30);  // a parallelogram with one vertex below the horizon
    EXPECT_GE(none, 3);
    EXPECT_GT(inLanes, 1000);
  }
}

// The lanes' azimuth intervals are ProjectedPolygon::azimuthIntervals' for every vertex count and every
// order of pseudo-angles drawn from three values (each of 3^3 + 3^4 + 3^5 arrays: ties of two, three
// and more vertices, ties at the lowest and the highest azimuth), on every instruction set.
TEST(PacketProjectedPolygon, AzimuthIntervalsAreTheScalarOnes) {
  for (const std::string& target : availablePacketTargets()) {
    ForcedTarget forced(target);
    const int lanes = std::min(packetLanes(), kMaxPacketLanes);
    std::vector<std::pair<int, std::array<double, 5>>> cases;
    for (int count = 3; count <= 5; ++count) {
      int arrays = 1;
      for (int i = 0; i < count; ++i) arrays *= 3;
      for (int code = 0; code < arrays; ++code) {
        std::array<double, 5> alpha{9, 9, 9, 9, 9};  // absent vertices: values no present one has
        for (int i = 0, c = code; i < count; ++i, c /= 3) alpha[size_t(i)] = -1.5 + c % 3;
        cases.push_back({count, alpha});
      }
    }
    int withIntervals = 0;
    for (size_t first = 0; first < cases.size(); first += size_t(lanes)) {
      double alpha[5][kMaxPacketLanes], count[kMaxPacketLanes], intervals[4][4][kMaxPacketLanes];
      for (int k = 0; k < lanes; ++k) {
        const auto& c = cases[std::min(first + size_t(k), cases.size() - 1)];
        count[k] = c.first;
        for (int i = 0; i < 5; ++i) alpha[i][k] = c.second[size_t(i)];
      }
      packetKernels().azimuthIntervals(alpha, count, intervals);
      for (int k = 0; k < lanes && first + size_t(k) < cases.size(); ++k) {
        const auto& c = cases[first + size_t(k)];
        SCOPED_TRACE(target + " case " + std::to_string(first + size_t(k)));
        ProjectedPolygon::AzimuthInterval expected[ProjectedPolygon::kMaxVertices];
        const int found = ProjectedPolygon::azimuthIntervals(c.second.data(), c.first, expected);
        int next = 0;
        for (int s = 0; s < 4; ++s) {
          if (intervals[s][0][k] < 0) {
            ASSERT_EQ(intervals[s][1][k], -1);
            continue;
          }
          ASSERT_LT(next, found);
          EXPECT_EQ(intervals[s][0][k], expected[next].from);
          EXPECT_EQ(intervals[s][1][k], expected[next].to);
          EXPECT_EQ(intervals[s][2][k], expected[next].edgeA);
          EXPECT_EQ(intervals[s][3][k], expected[next].edgeB);
          ++next;
        }
        ASSERT_EQ(next, found);
        withIntervals += found > 0;
      }
    }
    EXPECT_EQ(withIntervals, 27 + 81 + 243 - 9);  // all but the three arrays of equal values per count
  }
}

}  // namespace
}  // namespace penumbra
