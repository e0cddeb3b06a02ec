#include "core/render/packet_row_loop.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "core/render/film.h"
#include "core/render/packet_camera.h"
#include "core/render/packet_kernels.h"
#include "core/render/packet_queries.h"
#include "core/render/packet_streams.h"
#include "core/sampling/sampler.h"

namespace penumbra {

namespace {

// At most this much of a worker's draws for the packets of one query.
inline constexpr size_t kMaxGroupDrawBytes = size_t(1) << 19;

struct PacketWeights {
  float w[kMaxPacketLanes];
};

// One per row renderer (per worker thread), reused packet after packet: the draws, camera rays, filter
// weights and (where queried) hits of the packets whose camera rays are queried together (one packet
// where the kernel finds the hits itself).
struct PacketBuffers {
  PacketBuffers(int packets, size_t drawCount)
      : rays(size_t(packets)), hits(size_t(packets)), weight(size_t(packets)) {
    for (int i = 0; i < packets; ++i) drawBuffers.emplace_back(drawCount);
    // Views taken once the buffers are in place (a move of the vector keeps each buffer's storage).
    for (PacketDrawBuffer& buffer : drawBuffers) draws.push_back(buffer.draws());
  }
  float filterU[2][kMaxPacketLanes];
  PacketStreamStart start;
  std::vector<PacketRays> rays;
  std::vector<PacketHitLanes> hits;
  std::vector<PacketWeights> weight;
  std::vector<PacketDrawBuffer> drawBuffers;
  std::vector<PacketDraws> draws;
  PacketRadiance radiance;
};

// How many packets' camera rays go to one query (queryCameraHits: up to kQueriedCameraRays rays).
int packetsPerQuery(const PacketScene& scene, int lanes, size_t drawCount) {
  if (!scene.geometryQueried) return 1;
  const size_t drawBytes = std::max<size_t>(drawCount, 1) * sizeof(PacketDraw);
  const size_t byDraws = std::max<size_t>(kMaxGroupDrawBytes / drawBytes, 1);
  return int(std::min<size_t>(size_t(std::max(kQueriedCameraRays / lanes, 1)), byDraws));
}

}  // namespace

bool packetPathEnabled() {
  static const bool enabled = [] {
    const char* value = std::getenv("PENUMBRA_SIMD");
    const std::string name = value ? value : "";
    if (name == "off") return false;
    if (!forcePacketTarget(name)) {
      std::string names;
      for (const std::string& t : availablePacketTargets()) names += " " + t;
      std::fprintf(stderr,
                   "penumbra: PENUMBRA_SIMD=%s is not an instruction set of this CPU (one of:%s, "
                   "auto, off); using the best one\n",
                   name.c_str(), names.c_str());
    }
    return true;
  }();
  return enabled;
}

RowRenderer packetRowsFor(const RenderJob& job, RowRenderer scalar) {
  auto filter = std::make_shared<const FilterSampler>(job.settings.filter);
  const PacketCamera camera = makePacketCamera(PerspectiveCamera(job.settings.camera), *filter);
  const int width = job.settings.camera.width;
  auto scene = std::make_shared<const PacketScene>(makePacketScene(job));
  auto plan = std::make_shared<const DrawPlan>(drawPlan(scene->draws));
  const int lanes = std::min(packetLanes(), kMaxPacketLanes);
  // The plan's first call is the filter's draw, which goes to filterU.
  const size_t drawCount = plan->calls.size() - 1;
  const int group = packetsPerQuery(*scene, lanes, drawCount);
  auto buffers = std::make_shared<PacketBuffers>(group, drawCount);
  const PacketKernels& kernels = packetKernels();
  RowRenderer r;
  r.row = [camera, width, filter, scene, plan, buffers, lanes, group, kernels](
              int y, uint32_t pass, Sampler& sampler, Film& film, uint64_t& badSamples,
              const std::atomic<bool>& cancel) {
    PacketBuffers& b = *buffers;
    const PacketDrawPlan draws = plan->view();
    startPacketStreamRow(sampler, pass, b.start);
    for (int x0 = 0; x0 < width; x0 += lanes * group) {
      if (cancel.load(std::memory_order_relaxed)) return;
      // Each lane's draws in startCameraSample's order: the filter's, then the integrator's, drawn
      // whatever the ray hits (each pixel sample restarts its stream, so draws a lane does not use
      // change nothing). Lanes past the row's end repeat its last pixel; their results are dropped.
      const int packets = std::min(group, (width - x0 + lanes - 1) / lanes);
      for (int i = 0; i < packets; ++i) {
        const int x = x0 + i * lanes, count = std::min(lanes, width - x);
        startPacketStreams(x, y, count, lanes, b.start);
        kernels.samplerDraws(b.start, draws, b.filterU, b.draws[size_t(i)]);
        kernels.cameraRays(camera, x, y, count, b.filterU, b.rays[size_t(i)], b.weight[size_t(i)].w);
      }
      if (scene->geometryQueried)
        queryCameraHits(*scene->scene, b.rays.data(), packets, lanes, b.hits.data());
      for (int i = 0; i < packets; ++i) {
        const int x = x0 + i * lanes, count = std::min(lanes, width - x);
        kernels.shade(*scene, b.rays[size_t(i)], &b.hits[size_t(i)], b.draws[size_t(i)], b.radiance);
        badSamples += kernels.filmAdd(b.radiance, b.weight[size_t(i)].w, count, film.sumsAt(x, y));
      }
    }
  };
  r.preview = std::move(scalar.preview);
  return r;
}

}  // namespace penumbra
