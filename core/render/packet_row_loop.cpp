#include "core/render/packet_row_loop.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "core/math/float_util.h"
#include "core/render/film.h"
#include "core/render/packet_camera.h"
#include "core/render/packet_kernels.h"
#include "core/sampling/morton.h"
#include "core/sampling/rng.h"
#include "core/sampling/sampler.h"
#include "core/sampling/sobol_stream.h"

namespace penumbra {

namespace {

// One per row renderer (per worker thread), reused packet after packet.
struct PacketBuffers {
  float filterU[2][kMaxPacketLanes];
  PacketSobolStart sobolStart;
  PacketRays rays;
  PacketDraws draws;
  PacketRadiance radiance;
  float weight[kMaxPacketLanes];
};

// A camera sample's sampler calls in the integrator's order: the filter's next2D() first, then the
// scene's draw requests unrolled, one call each; and the request each takes in the Sobol' streams.
struct DrawPlan {
  std::vector<SobolDrawCall> calls;
  std::vector<uint32_t> sobolRequests;
  int shadingDraws() const { return int(calls.size()) - 1; }
};

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

// Each lane's start of the Sobol' samplers' stream for pixels x0 .. x0 + count - 1 of row y
// (BasicSobolStream::startSobol and startZSobol); the start's other fields are set once per row.
void startSobolLanes(uint64_t seedHash, int x0, int y, int count, int lanes, PacketSobolStart& start) {
  const auto py = uint32_t(y);
  constexpr uint32_t side = (1u << kZSobolTileSideBits) - 1;
  for (int k = 0; k < lanes; ++k) {
    const auto px = uint32_t(x0 + std::min(k, count - 1));
    if (start.zsobol) {
      start.key[k] =
          hashCombine(seedHash, encodeMorton2(px >> kZSobolTileSideBits, py >> kZSobolTileSideBits));
      start.reversedTileCode[k] = kZSobolReversedSpread[px & side] | kZSobolReversedSpread[py & side] >> 1;
    } else {
      start.key[k] = hashCombine(seedHash, (uint64_t(px) << 32) | py);
      start.reversedTileCode[k] = 0;
    }
  }
}

// Each lane's filter draw and shading draws from the scalar sampler, lane by lane (lanes past `count`
// repeat the last pixel).
void drawLaneByLane(Sampler& sampler, const DrawPlan& plan, int x0, int y, int count, int lanes,
                    uint32_t pass, PacketBuffers& b) {
  for (int k = 0; k < lanes; ++k) {
    sampler.startPixelSample(IVec2(x0 + std::min(k, count - 1), y), pass);
    for (size_t i = 0; i < plan.calls.size(); ++i) {
      const SobolDrawCall& c = plan.calls[i];
      const Vec2 v = c.m == 1 ? sampler.next2D(c.j, c.n) : sampler.next2D(c.j, c.n, c.k, c.m);
      float(&u)[2][kMaxPacketLanes] = i == 0 ? b.filterU : b.draws.u[i - 1];
      u[0][k] = v.x;
      u[1][k] = v.y;
    }
  }
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
  auto buffers = std::make_shared<PacketBuffers>();
  const int lanes = std::min(packetLanes(), kMaxPacketLanes);
  const PacketKernels& kernels = packetKernels();
  RowRenderer r;
  r.row = [camera, width, filter, scene, plan, buffers, lanes, kernels](
              int y, uint32_t pass, Sampler& sampler, Film& film, uint64_t& badSamples,
              const std::atomic<bool>& cancel) {
    PacketBuffers& b = *buffers;
    const SamplerKind kind = sampler.kind();
    const uint64_t seedHash = mix64(sampler.seed());
    b.sobolStart.zsobol = kind == SamplerKind::ZSobol;
    b.sobolStart.log2Samples = zsobolLog2Samples(sampler.sampleCount());
    b.sobolStart.pass = pass;
    for (int x0 = 0; x0 < width; x0 += lanes) {
      if (cancel.load(std::memory_order_relaxed)) return;
      const int count = std::min(lanes, width - x0);
      // Each lane's draws in startCameraSample's order: the filter's, then the integrator's, drawn
      // whatever the ray hits (each pixel sample restarts its stream, so draws a lane does not use
      // change nothing). Lanes past the row's end repeat its last pixel; their results are dropped.
      // The independent and Sobol' samplers draw in lanes, the stratified one lane by lane.
      if (kind == SamplerKind::Independent) {
        kernels.independentDraws(seedHash, x0, y, count, pass, plan->shadingDraws(), b.filterU, b.draws);
      } else if (kind == SamplerKind::Sobol || kind == SamplerKind::ZSobol) {
        startSobolLanes(seedHash, x0, y, count, lanes, b.sobolStart);
        kernels.sobolDraws(b.sobolStart, plan->calls.data(), plan->sobolRequests.data(),
                           int(plan->calls.size()), b.filterU, b.draws);
      } else {
        drawLaneByLane(sampler, *plan, x0, y, count, lanes, pass, b);
      }
      kernels.cameraRays(camera, x0, y, count, b.filterU, b.rays, b.weight);
      kernels.shade(*scene, b.rays, b.draws, b.radiance);
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
