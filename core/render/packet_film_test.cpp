#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/math/float_util.h"
#include "core/render/film.h"
#include "core/render/packet_kernels.h"
#include "core/render/packet_target_test_support.h"
#include "core/sampling/rng.h"

namespace penumbra {
namespace {

using test::ForcedTarget;

// The film kernel adds what the scalar row loop adds, bit for bit, on every instruction set: each valid
// lane's radiance times its (possibly negative) filter weight and its square, in double, into its
// pixel's sums; lanes with a NaN, an infinite or a negative channel (or channels whose sum
// overflows) add nothing and are counted; lanes past `count` are not touched.
TEST(PacketFilm, AddsWhatFilmAddAddsAndCountsInvalidLanes) {
  constexpr float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  const float odd[] = {nan, inf, -inf, -1e-30f, -0.f, 0.f, 3e38f, 1e-45f};
  for (const std::string& target : availablePacketTargets()) {
    ForcedTarget forced(target);
    const int lanes = std::min(packetLanes(), kMaxPacketLanes);
    Rng rng(7, 3);
    uint32_t invalidSeen = 0;
    for (int trial = 0; trial < 2000; ++trial) {
      const int count = 1 + int(rng.nextU32() % uint32_t(lanes));
      const int width = lanes + 2;
      Film scalar(width, 1), packet(width, 1);
      for (size_t i = 0; i < scalar.sums().size(); ++i)
        scalar.sums()[i] = packet.sums()[i] = rng.nextDouble();
      PacketRadiance radiance;
      float weight[kMaxPacketLanes];
      for (int k = 0; k < kMaxPacketLanes; ++k) {
        for (int c = 0; c < 3; ++c)
          radiance.L[c][k] = rng.nextU32() % 5 == 0 ? odd[rng.nextU32() % 8] : rng.nextFloat() * 10.f;
        weight[k] = rng.nextFloat() * 2.f - 0.5f;
      }
      const int x0 = 1;
      uint32_t scalarInvalid = 0;
      for (int k = 0; k < count; ++k) {
        const Color3 L(radiance.L[0][k], radiance.L[1][k], radiance.L[2][k]);
        if (isValidRadiance(L))
          scalar.add(x0 + k, 0, L * weight[k]);
        else
          ++scalarInvalid;
      }
      const uint32_t invalid = packetKernels().filmAdd(radiance, weight, count, packet.sumsAt(x0, 0));
      ASSERT_EQ(invalid, scalarInvalid) << target << " trial " << trial;
      for (size_t i = 0; i < scalar.sums().size(); ++i)
        ASSERT_EQ(std::bit_cast<uint64_t>(packet.sums()[i]), std::bit_cast<uint64_t>(scalar.sums()[i]))
            << target << " trial " << trial << " sum " << i;
      invalidSeen += invalid;
    }
    EXPECT_GT(invalidSeen, 500u) << target;  // the odd values do reach the kernel
  }
}

}  // namespace
}  // namespace penumbra
