// Each lane's sample stream in the packet row loop: which sampler calls a camera sample makes (the
// draw plan, unrolled once per render) and where each lane's stream starts (per packet).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/render/packet_kernels.h"
#include "core/render/packet_scene.h"
#include "core/sampling/rng.h"
#include "core/sampling/sampler.h"
#include "core/sampling/sobol_stream.h"

namespace penumbra {

// A camera sample's sampler calls in the integrator's order: the filter's next2D() first, then the
// scene's draw requests unrolled, one call each; and the request each takes in the Sobol' streams.
struct DrawPlan {
  std::vector<SobolDrawCall> calls;
  std::vector<uint32_t> sobolRequests;
  PacketDrawPlan view() const { return {calls.data(), sobolRequests.data(), int(calls.size())}; }
};

DrawPlan drawPlan(const std::vector<DrawRequests>& requests);

// The fields of a packet's stream start that stay for a row: `sampler`'s kind and settings at sample
// index `pass`.
void startPacketStreamRow(const Sampler& sampler, uint32_t pass, PacketStreamStart& start);

// Each lane's word of the stream start for pixels x0 .. x0 + count - 1 of row y, as
// Sampler::startPixelSample computes it (after startPacketStreamRow); lanes past `count` (up to
// `lanes`) repeat the last pixel.
inline void startPacketStreams(int x0, int y, int count, int lanes, PacketStreamStart& start) {
  const auto py = uint32_t(y);
  const auto lastX = uint32_t(x0 + count - 1);
  if (start.kind == SamplerKind::ZSobol) {
    for (int k = 0; k < lanes; ++k) {
      const uint32_t px = std::min(uint32_t(x0 + k), lastX);
      start.word[k] = zsobolTileWord(px, py);
      start.reversedTileCode[k] = zsobolReversedTileCode(px, py);
    }
  } else {
    for (int k = 0; k < lanes; ++k) start.word[k] = pixelStreamWord(std::min(uint32_t(x0 + k), lastX), py);
  }
}

}  // namespace penumbra
