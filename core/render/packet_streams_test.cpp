#include "core/render/packet_streams.h"

#include <gtest/gtest.h>

#include <bit>
#include <string>

#include "core/render/packet_target_test_support.h"
#include "core/sampling/sampler_table.h"

namespace penumbra {
namespace {

using test::ForcedTarget;

// Each lane's draws of the packet kernels equal the scalar Sampler's bit for bit, for every sampler
// kind on every instruction set: sample counts whose strata are not a power of two (Kensler's
// permutation walks its cycles) and are, sample indices in later epochs of the strata and near 2^32,
// pixels far from the origin and across zsobol's tiles, partial packets, and a plan of plain, array
// and interleaved calls as the integrators make them.
TEST(PacketStreams, DrawsEqualTheScalarSamplerForEveryKind) {
  const DrawPlan plan = drawPlan({{2, 1}, {1, 4}, {1, 3, 2}, {3, 1}, {1, 5, 3}});
  ASSERT_EQ(plan.calls.size(), 1u + 2 + 4 + 6 + 3 + 15);
  const uint32_t passes[] = {0, 1, 2, 8, 9, 10, 37, 1000, 123456789, 0xfffffffeu};
  const struct { int x0, y; } origins[] = {{0, 0}, {61, 7}, {4093, 4097}, {1 << 20, 3}};
  int compared = 0;
  for (const std::string& target : availablePacketTargets()) {
    ForcedTarget forced(target);
    const int lanes = std::min(packetLanes(), kMaxPacketLanes);
    const PacketKernels& kernels = packetKernels();
    for (int kind = 0; kind < kSamplerKindCount; ++kind)
      for (const uint32_t sampleCount : {1u, 3u, 8u, 10u, 17u, 100u, 1000u})
        for (const uint64_t seed : {0ull, 5ull, 0x123456789abcdefull}) {
          const Sampler probe(SamplerKind(kind), sampleCount, seed);
          for (const uint32_t pass : passes)
            for (const auto& o : origins)
              for (const int count : {lanes, 1, std::max(lanes - 1, 1)}) {
                PacketStreamStart start;
                startPacketStreamRow(probe, pass, start);
                startPacketStreams(o.x0, o.y, count, lanes, start);
                float filterU[2][kMaxPacketLanes];
                PacketDrawBuffer buffer(plan.calls.size() - 1);
                PacketDraws draws = buffer.draws();
                kernels.samplerDraws(start, plan.view(), filterU, draws);
                Sampler sampler(SamplerKind(kind), sampleCount, seed);
                for (int k = 0; k < lanes; ++k) {
                  sampler.startPixelSample(IVec2(o.x0 + std::min(k, count - 1), o.y), pass);
                  for (size_t i = 0; i < plan.calls.size(); ++i) {
                    const SobolDrawCall& c = plan.calls[i];
                    const Vec2 v = c.m == 1 ? sampler.next2D(c.j, c.n) : sampler.next2D(c.j, c.n, c.k, c.m);
                    const float* u[2] = {i == 0 ? filterU[0] : draws.draw[i - 1].u[0],
                                         i == 0 ? filterU[1] : draws.draw[i - 1].u[1]};
                    ASSERT_EQ(std::bit_cast<uint32_t>(u[0][k]), std::bit_cast<uint32_t>(v.x))
                        << target << " " << samplerKindName(SamplerKind(kind)) << " samples " << sampleCount
                        << " seed " << seed << " pass " << pass << " pixel " << o.x0 + k << "," << o.y
                        << " call " << i;
                    ASSERT_EQ(std::bit_cast<uint32_t>(u[1][k]), std::bit_cast<uint32_t>(v.y))
                        << target << " " << samplerKindName(SamplerKind(kind)) << " samples " << sampleCount
                        << " seed " << seed << " pass " << pass << " pixel " << o.x0 + k << "," << o.y
                        << " call " << i;
                    ++compared;
                  }
                }
              }
        }
  }
  EXPECT_GT(compared, 100000);
}

}  // namespace
}  // namespace penumbra
