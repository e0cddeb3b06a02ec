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
#include "core/render/packet_streams.h"
#include "core/sampling/sampler.h"

namespace penumbra {

namespace {

// One per row renderer (per worker thread), reused packet after packet.
struct PacketBuffers {
  explicit PacketBuffers(size_t drawCount) : drawBuffer(drawCount), draws(drawBuffer.draws()) {}
  float filterU[2][kMaxPacketLanes];
  PacketStreamStart start;
  PacketRays rays;
  PacketDrawBuffer drawBuffer;
  PacketDraws draws;
  PacketRadiance radiance;
  float weight[kMaxPacketLanes];
};

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
  // The plan's first call is the filter's draw, which goes to filterU.
  auto buffers = std::make_shared<PacketBuffers>(plan->calls.size() - 1);
  const int lanes = std::min(packetLanes(), kMaxPacketLanes);
  const PacketKernels& kernels = packetKernels();
  RowRenderer r;
  r.row = [camera, width, filter, scene, plan, buffers, lanes, kernels](
              int y, uint32_t pass, Sampler& sampler, Film& film, uint64_t& badSamples,
              const std::atomic<bool>& cancel) {
    PacketBuffers& b = *buffers;
    const PacketDrawPlan draws = plan->view();
    startPacketStreamRow(sampler, pass, b.start);
    for (int x0 = 0; x0 < width; x0 += lanes) {
      if (cancel.load(std::memory_order_relaxed)) return;
      const int count = std::min(lanes, width - x0);
      // Each lane's draws in startCameraSample's order: the filter's, then the integrator's, drawn
      // whatever the ray hits (each pixel sample restarts its stream, so draws a lane does not use
      // change nothing). Lanes past the row's end repeat its last pixel; their results are dropped.
      startPacketStreams(x0, y, count, lanes, b.start);
      kernels.samplerDraws(b.start, draws, b.filterU, b.draws);
      kernels.cameraRays(camera, x0, y, count, b.filterU, b.rays, b.weight);
      kernels.shade(*scene, b.rays, b.draws, b.radiance);
      badSamples += kernels.filmAdd(b.radiance, b.weight, count, film.sumsAt(x0, y));
    }
  };
  r.preview = std::move(scalar.preview);
  return r;
}

}  // namespace penumbra
