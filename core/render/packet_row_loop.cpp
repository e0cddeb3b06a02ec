#include "core/render/packet_row_loop.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "core/math/float_util.h"
#include "core/render/packet_kernels.h"
#include "core/render/row_loop.h"

namespace penumbra {

namespace {

// One per row renderer (per worker thread), reused packet after packet.
struct PacketBuffers {
  PacketRays rays;
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
  PerspectiveCamera camera(job.settings.camera);
  FilterSampler filter(job.settings.filter);
  auto scene = std::make_shared<const PacketScene>(makePacketScene(job));
  auto buffers = std::make_shared<PacketBuffers>();
  const int lanes = std::min(packetLanes(), kMaxPacketLanes);
  const PacketShader shade = packetShader();
  RowRenderer r;
  r.row = [camera, filter, scene, buffers, lanes, shade](int y, uint32_t pass, Sampler& sampler, Film& film,
                                                         uint64_t& badSamples,
                                                         const std::atomic<bool>& cancel) {
    PacketBuffers& b = *buffers;
    const int width = camera.width();
    for (int x0 = 0; x0 < width; x0 += lanes) {
      if (cancel.load(std::memory_order_relaxed)) return;
      const int count = std::min(lanes, width - x0);
      for (int k = 0; k < lanes; ++k) {
        // Lanes past the row's end repeat its last pixel; their results are dropped.
        const int x = x0 + std::min(k, count - 1);
        const Ray ray = startCameraSample(camera, filter, sampler, x, y, pass, b.weight[k]);
        for (int c = 0; c < 3; ++c) {
          b.rays.o[c][k] = ray.o[c];
          b.rays.d[c][k] = ray.d[c];
        }
        b.rays.tMin[k] = ray.tMin;
        b.rays.tMax[k] = ray.tMax;
        // The integrator's draws in its order, drawn whatever the ray hits: each pixel sample
        // restarts its stream, so draws a lane does not use change nothing.
        int j = 0;
        for (const DrawRequests& r : scene->draws)
          for (int rep = 0; rep < r.repeats; ++rep)
            for (int i = 0; i < r.n; ++i)
              for (int part = 0; part < r.parts; ++part, ++j) {
                const Vec2 u = r.parts == 1 ? sampler.next2D(uint32_t(i), uint32_t(r.n))
                                            : sampler.next2D(uint32_t(i), uint32_t(r.n), uint32_t(part),
                                                             uint32_t(r.parts));
                b.draws.u[j][0][k] = u.x;
                b.draws.u[j][1][k] = u.y;
              }
      }
      shade(*scene, b.rays, b.draws, b.radiance);
      for (int k = 0; k < count; ++k) {
        const Color3 L(b.radiance.L[0][k], b.radiance.L[1][k], b.radiance.L[2][k]);
        // NaN, Inf or negative radiance is a bug somewhere: count it and add nothing.
        if (isValidRadiance(L))
          film.add(x0 + k, y, L * b.weight[k]);
        else
          ++badSamples;
      }
    }
  };
  r.preview = std::move(scalar.preview);
  return r;
}

}  // namespace penumbra
