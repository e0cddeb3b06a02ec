#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/integrators/polygon_light_technique.h"
#include "core/integrators/shading_point.h"
#include "core/lights/polygon_light.h"
#include "core/render/packet_kernels.h"
#include "core/render/packet_polygon_settings_test_support.h"
#include "core/render/packet_scene.h"
#include "core/render/packet_target_test_support.h"
#include "core/sampling/rng.h"

namespace penumbra {
namespace {

using test::ForcedTarget;
using test::Setting;

// A direction from a setting's shading point towards its light, and the point it is taken to reach.
struct Towards {
  Vec3 w, p;
};

// Directions of every kind a density meets: the technique's own sample (inside), towards a vertex and
// towards an edge's midpoint (on the boundary, to rounding), just outside an edge, and anywhere.
enum class Aim { Sample, Vertex, EdgeMidpoint, JustOutside, Anywhere, Count };

template <LightMeasure kMeasure>
Towards aim(const Setting& s, Aim kind, Rng& rng) {
  Vec3 v[4];
  s.light.vertices(v);
  const int count = s.light.vertexCount();
  const int i = int(rng.nextU32() % uint32_t(count)), j = (i + 1) % count;
  Vec3 target;
  switch (kind) {
    case Aim::Sample: {
      const LightTechnique<kMeasure, PolygonLight> technique(s.light,
                                                             ShadingPoint::facing(s.x, s.n, s.n, 1.f));
      if (technique.canSample()) {
        const LightSample sample = technique.sample(Vec2(rng.nextFloat(), rng.nextFloat()));
        if (sample.pdf > 0.f) return {sample.wi, sample.p};
      }
      target = v[i];
      break;
    }
    case Aim::Vertex:
      target = v[i];
      break;
    case Aim::EdgeMidpoint:
      target = 0.5f * (v[i] + v[j]);
      break;
    case Aim::JustOutside: {
      // Past the edge's midpoint, away from the opposite vertex, by 10⁻⁶ to 10⁻² of the edge.
      const Vec3 mid = 0.5f * (v[i] + v[j]), away = mid - v[(j + 1) % count];
      target = mid + std::pow(10.f, -6.f + 4.f * rng.nextFloat()) * away;
      break;
    }
    default: {
      const Vec3 w = test::randomUnit(rng);
      return {w, s.x + w};
    }
  }
  const Vec3 d = target - s.x;
  const float len = glm::length(d);
  return {len > 0.f ? d / len : Vec3(0.f, 0.f, 1.f), target};
}

// The lanes' light density of each measure is LightTechnique<measure, PolygonLight>::pdf's, bit for bit,
// on every instruction set, for directions inside each polygon light, on its boundary, just outside and
// anywhere; lanes left to the scalar technique are those the lanes cannot map (none by area or by the
// projected solid angle, which clips polygons reaching below the horizon in lanes).
template <LightMeasure kMeasure>
void expectScalarDensities() {
  Rng settingRng(11, 3);
  const std::vector<Setting> all = test::polygonSettings(settingRng);
  for (const std::string& target : availablePacketTargets()) {
    ForcedTarget forced(target);
    const int lanes = std::min(packetLanes(), kMaxPacketLanes);
    Rng rng(7, 2);
    std::array<int, size_t(Aim::Count)> positive{}, zero{};
    int byScalar = 0, clippedPositive = 0;
    for (size_t first = 0; first < all.size(); first += size_t(lanes)) {
      const test::SettingLanes packet = test::settingLanes(all, first, lanes);
      const auto& polygons = packet.polygons;
      const auto &x = packet.x, &n = packet.n;
      const auto& active = packet.active;
      for (int kind = 0; kind < int(Aim::Count); ++kind) {
        float w[3][kMaxPacketLanes] = {}, p[3][kMaxPacketLanes] = {}, pdf[kMaxPacketLanes],
              scalarLanes[kMaxPacketLanes];
        for (int k = 0; k < lanes; ++k) {
          const Towards t = aim<kMeasure>(all[std::min(first + size_t(k), all.size() - 1)], Aim(kind), rng);
          for (int c = 0; c < 3; ++c) w[c][k] = t.w[c], p[c][k] = t.p[c];
        }
        packetKernels().polygonLightPdfs(kMeasure, polygons, x, n, active, w, p, pdf, scalarLanes);
        for (int k = 0; k < lanes; ++k) {
          if (active[k] == 0.f) continue;
          const size_t index = first + size_t(k);
          SCOPED_TRACE(target + " setting " + std::to_string(index) + " aim " + std::to_string(kind));
          const Setting& s = all[index];
          if (scalarLanes[k] != 0.f) {
            ASSERT_EQ(kMeasure, LightMeasure::SolidAngle);
            ASSERT_EQ(pdf[k], 0.f);
            byScalar += kind == 0;
            continue;
          }
          const LightTechnique<kMeasure, PolygonLight> technique(s.light,
                                                                 ShadingPoint::facing(s.x, s.n, s.n, 1.f));
          const Vec3 wk(w[0][k], w[1][k], w[2][k]), pk(p[0][k], p[1][k], p[2][k]);
          ASSERT_EQ(pdf[k], technique.pdf(wk, pk, s.light.n));
          ++(pdf[k] > 0.f ? positive : zero)[size_t(kind)];
          clippedPositive += pdf[k] > 0.f && !(test::lowestVertexHeight(s) > 0.0);
        }
      }
    }
    SCOPED_TRACE(target);
    // Directions inside and on the boundary met positive densities in lanes; by a direction map, those
    // on the boundary, outside and anywhere met zero ones too.
    for (const Aim kind : {Aim::Sample, Aim::Vertex, Aim::EdgeMidpoint}) {
      EXPECT_GT(positive[size_t(kind)], 100) << int(kind);
    }
    if (kMeasure != LightMeasure::Area) {
      for (const Aim kind : {Aim::Vertex, Aim::EdgeMidpoint, Aim::JustOutside, Aim::Anywhere}) {
        EXPECT_GT(zero[size_t(kind)], 100) << int(kind);
      }
    }
    // The solid angle leaves sheared and tiny polygons to the scalar technique; the projected solid
    // angle maps every polygon in lanes, those reaching below the horizon clipped.
    if (kMeasure == LightMeasure::SolidAngle) {
      EXPECT_GT(byScalar, 100);
    }
    EXPECT_GT(clippedPositive, 100);
  }
}

TEST(PacketPolygonTechniques, AreaDensityIsTheScalarTechniques) {
  expectScalarDensities<LightMeasure::Area>();
}
TEST(PacketPolygonTechniques, SolidAngleDensityIsTheScalarTechniques) {
  expectScalarDensities<LightMeasure::SolidAngle>();
}
TEST(PacketPolygonTechniques, ProjectedSolidAngleDensityIsTheScalarTechniques) {
  expectScalarDensities<LightMeasure::ProjectedSolidAngle>();
}

}  // namespace
}  // namespace penumbra
