#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/lights/alias_table.h"
#include "core/lights/light_selection.h"
#include "core/render/packet_kernels.h"
#include "core/render/packet_target_test_support.h"
#include "core/sampling/rng.h"

namespace penumbra {
namespace {

using test::ForcedTarget;

// The floats a pick draw is made of: random ones, and the ones at the table's edges (0, the largest
// float below 1 in both halves, each bin's lower edge and the float just below it).
std::vector<std::array<float, 2>> pickDraws(uint32_t bins, Rng& rng) {
  std::vector<std::array<float, 2>> u;
  const float belowOne = std::nextafter(1.f, 0.f);
  u.push_back({0.f, 0.f});
  u.push_back({belowOne, belowOne});
  u.push_back({belowOne, 0.f});
  for (uint32_t i = 1; i < bins && i < 64; ++i) {
    const float edge = float(i) / float(bins);
    u.push_back({edge, 0.f});
    u.push_back({std::nextafter(edge, 0.f), belowOne});
  }
  for (int i = 0; i < 2000; ++i) u.push_back({rng.nextFloat(), rng.nextFloat()});
  return u;
}

// Every draw of `u` through the kernel, a packet at a time with every third lane inactive, against
// `selection.pick` (the scalar estimator's pick: nothing where its pmf is not positive).
template <class Selection>
void expectPicksEqual(const Selection& selection, const PacketLightTable& table,
                      const std::vector<std::array<float, 2>>& u, const std::string& what) {
  const int lanes = std::min(packetLanes(), kMaxPacketLanes);
  for (size_t first = 0; first < u.size(); first += size_t(lanes)) {
    float draws[2][kMaxPacketLanes] = {}, active[kMaxPacketLanes] = {}, light[kMaxPacketLanes];
    double pmf[kMaxPacketLanes];
    for (int k = 0; k < lanes && first + size_t(k) < u.size(); ++k) {
      draws[0][k] = u[first + size_t(k)][0];
      draws[1][k] = u[first + size_t(k)][1];
      active[k] = (first + size_t(k)) % 3 == 2 ? 0.f : 1.f;
    }
    packetKernels().tablePicks(table, draws, active, light, pmf);
    for (int k = 0; k < lanes && first + size_t(k) < u.size(); ++k) {
      const LightPick pick =
          selection.pick(Vec3(0.f), Vec3(0.f), double(draws[0][k]) + double(draws[1][k]) * 0x1p-24);
      const bool some = active[k] != 0.f && pick.pmf > 0.0;
      SCOPED_TRACE(what + " draw " + std::to_string(first + size_t(k)));
      ASSERT_EQ(light[k], some ? float(pick.light) : -1.f);
      ASSERT_EQ(pmf[k], some ? pick.pmf : 0.0);
    }
  }
}

// Uniform and power selection pick in lanes what they pick one sample at a time, bit for bit, on every
// instruction set: tables of 1 to 1000 lights, powers spanning 1e-300 to 1e300, lights of zero power
// (the estimator skips them) and every weight zero (uniform), draws at every bin's edge and at 1⁻.
TEST(PacketLightTable, PicksWhatTheScalarSelectionsPick) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::vector<double>> powerTables = {
      {1.0},
      {0.0, 0.0, 0.0},
      {3.0, 0.0, 1.0},
      {1e-300, 1e300, 1.0, 0.0},
      {nan, 2.0, -1.0, 5.0, std::numeric_limits<double>::infinity()},
  };
  for (const std::string& target : availablePacketTargets()) {
    ForcedTarget forced(target);
    Rng rng(11, 5);
    for (const uint32_t count : {0u, 1u, 2u, 3u, 7u, 100u, 1000u}) {
      const UniformLightSelection uniform{count};
      expectPicksEqual(uniform, packetLightTable(uniform), pickDraws(count, rng),
                       target + " uniform " + std::to_string(count));
    }
    std::vector<std::vector<double>> tables = powerTables;
    for (const int n : {2, 17, 1000}) {
      std::vector<double> weights;
      for (int i = 0; i < n; ++i)
        weights.push_back(rng.nextU32() % 4 == 0 ? 0.0 : std::exp(20.0 * rng.nextDouble()));
      tables.push_back(weights);
    }
    for (size_t t = 0; t < tables.size(); ++t) {
      const PowerLightSelection power{makeAliasTable(tables[t])};
      expectPicksEqual(power, packetLightTable(power), pickDraws(power.table.size(), rng),
                       target + " power table " + std::to_string(t));
    }
    expectPicksEqual(PowerLightSelection{}, packetLightTable(PowerLightSelection{}), pickDraws(0, rng),
                     target + " power, no lights");
  }
}

}  // namespace
}  // namespace penumbra
