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

// One sampler request of a camera sample's shading draws: next2D(i, n), or next2D(i, n, part, parts)
// when parts > 1.
struct DrawIndex {
  uint32_t i, n, part, parts;
};

// The scene's draw requests unrolled into one entry per draw, in the integrator's order.
std::vector<DrawIndex> drawPlan(const std::vector<DrawRequests>& requests) {
  std::vector<DrawIndex> plan;
  for (const DrawRequests& r : requests)
    for (int rep = 0; rep < r.repeats; ++rep)
      for (int i = 0; i < r.n; ++i)
        for (int part = 0; part < r.parts; ++part)
          plan.push_back({uint32_t(i), uint32_t(r.n), uint32_t(part), uint32_t(r.parts)});
  return plan;
}

// The Sobol' samplers' calls of a camera sample (the filter's next2D(), then the plan's) and the
// request each draws with.
struct SobolPlan {
  std::vector<SobolDrawCall> calls;
  std::vector<uint32_t> requests;
};

SobolPlan sobolPlan(const std::vector<DrawIndex>& plan) {
  SobolPlan p;
  p.calls.push_back({0, 1, 0, 1});
  for (const DrawIndex& d : plan) p.calls.push_back({d.i, d.n, d.part, d.parts});
  p.requests = sobolRequests(p.calls);
  return p;
}

// Each lane's start of the Sobol' samplers' stream for pixels x0 .. x0 + count - 1 of row y
// (BasicSobolStream::startSobol and startZSobol).
void startSobolLanes(const Sampler& sampler, uint64_t seedHash, int x0, int y, int count, int lanes,
                     uint32_t pass, PacketSobolStart& start) {
  start.zsobol = sampler.kind() == SamplerKind::ZSobol;
  start.log2Samples = zsobolLog2Samples(sampler.sampleCount());
  start.pass = pass;
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
void drawLaneByLane(Sampler& sampler, const std::vector<DrawIndex>& plan, int x0, int y, int count, int lanes,
                    uint32_t pass, PacketBuffers& b) {
  for (int k = 0; k < lanes; ++k) {
    sampler.startPixelSample(IVec2(x0 + std::min(k, count - 1), y), pass);
    const Vec2 u = sampler.next2D();
    b.filterU[0][k] = u.x;
    b.filterU[1][k] = u.y;
    int j = 0;
    for (const DrawIndex& d : plan) {
      const Vec2 v = d.parts == 1 ? sampler.next2D(d.i, d.n) : sampler.next2D(d.i, d.n, d.part, d.parts);
      b.draws.u[j][0][k] = v.x;
      b.draws.u[j][1][k] = v.y;
      ++j;
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
  auto plan = std::make_shared<const std::vector<DrawIndex>>(drawPlan(scene->draws));
  auto sobol = std::make_shared<const SobolPlan>(sobolPlan(*plan));
  auto buffers = std::make_shared<PacketBuffers>();
  const int lanes = std::min(packetLanes(), kMaxPacketLanes);
  const PacketShader shade = packetShader();
  const PacketCameraRays cameraRays = packetCameraRays();
  const PacketIndependentDraws independentDraws = packetIndependentDraws();
  const PacketSobolDraws sobolDraws = packetSobolDraws();
  RowRenderer r;
  r.row = [camera, width, filter, scene, plan, sobol, buffers, lanes, shade, cameraRays, independentDraws,
           sobolDraws](int y, uint32_t pass, Sampler& sampler, Film& film, uint64_t& badSamples,
                       const std::atomic<bool>& cancel) {
    PacketBuffers& b = *buffers;
    const SamplerKind kind = sampler.kind();
    const uint64_t seedHash = mix64(sampler.seed());
    for (int x0 = 0; x0 < width; x0 += lanes) {
      if (cancel.load(std::memory_order_relaxed)) return;
      const int count = std::min(lanes, width - x0);
      // Each lane's draws in startCameraSample's order: the filter's, then the integrator's, drawn
      // whatever the ray hits (each pixel sample restarts its stream, so draws a lane does not use
      // change nothing). Lanes past the row's end repeat its last pixel; their results are dropped.
      // The independent and Sobol' samplers draw in lanes, the stratified one lane by lane.
      if (kind == SamplerKind::Independent) {
        independentDraws(seedHash, x0, y, count, pass, int(plan->size()), b.filterU, b.draws);
      } else if (kind == SamplerKind::Sobol || kind == SamplerKind::ZSobol) {
        startSobolLanes(sampler, seedHash, x0, y, count, lanes, pass, b.sobolStart);
        sobolDraws(b.sobolStart, sobol->calls.data(), sobol->requests.data(), int(sobol->calls.size()),
                   b.filterU, b.draws);
      } else {
        drawLaneByLane(sampler, *plan, x0, y, count, lanes, pass, b);
      }
      cameraRays(camera, x0, y, count, b.filterU, b.rays, b.weight);
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
