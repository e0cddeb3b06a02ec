#include "core/render/packet_streams.h"

#include <algorithm>
#include <iterator>

namespace penumbra {

DrawPlan drawPlan(const std::vector<DrawRequests>& requests) {
  DrawPlan plan;
  plan.calls.push_back({0, 1, 0, 1});
  for (const DrawRequests& r : requests)
    for (int rep = 0; rep < r.repeats; ++rep)
      for (int i = 0; i < r.n; ++i)
        for (int part = 0; part < r.parts; ++part)
          plan.calls.push_back({uint32_t(i), uint32_t(r.n), uint32_t(part), uint32_t(r.parts)});
  plan.sobolRequests = sobolRequests(plan.calls);
  return plan;
}

void startPacketStreamRow(const Sampler& sampler, uint32_t pass, PacketStreamStart& start) {
  start.kind = sampler.kind();
  start.pass = pass;
  start.gridSide = sampler.gridSide();
  start.log2Samples = sampler.zsobolLog2Samples();
  start.seedHash = sampler.seedHash();
  std::fill(std::begin(start.reversedTileCode), std::end(start.reversedTileCode), 0u);
}

}  // namespace penumbra
