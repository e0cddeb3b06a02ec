// The row loop of ambient occlusion in scenes whose geometry is in Embree's BVH: camera samples in
// batches of about kAoBatchRays visibility rays (at least one pixel), which are traced together as one stream
// (OcclusionBatch: rtcOccluded1M). The camera samples' draws, filter offsets and camera rays are made in
// SIMD packets as in the packet row loop. Each pixel's rays, their contributions and the order in which they
// are summed are those of AoIntegrator::Li, so the image equals the per-sample row loop's
// (row_loop.h) bit for bit; the batch only changes how Embree is asked.
#pragma once

#include <algorithm>
#include <atomic>
#include <memory>
#include <vector>

#include "core/geometry/occlusion_batch.h"
#include "core/integrators/ao_integrator.h"
#include "core/math/float_util.h"
#include "core/render/packet_camera.h"
#include "core/render/packet_kernels.h"
#include "core/render/packet_row_loop.h"
#include "core/render/packet_streams.h"
#include "core/render/row_loop.h"

namespace penumbra {

// Rays per batch: 256 pixels at 4 AO samples, a stream that Embree traverses well and that still
// fits in L2 (48 KB of Embree's rays). A batch is also the unit of cancellation.
inline constexpr int kAoBatchRays = 1024;

// Lane k's shading draws of a packet, handed to the integrator in place of the sampler: draw i of
// the integrator's one request of n.
struct PacketLaneDraws {
  const PacketDraws& draws;
  int lane;
  Vec2 next2D(uint32_t i, uint32_t /*n*/) const {
    return Vec2(draws.draw[i].u[0][lane], draws.draw[i].u[1][lane]);
  }
};

template <HemisphereWarp kWarp>
RowRenderer aoBatchRowsFor(const RenderJob& job, AoIntegrator<kWarp> integrator) {
  PerspectiveCamera camera(job.settings.camera);
  auto filter = std::make_shared<const FilterSampler>(job.settings.filter);
  const Scene* scene = job.scene.get();
  // The camera samples' draws and rays in SIMD lanes (packet_streams.h, the packet kernels), as the
  // packet row loop makes them, unless SIMD is off or the directions do not fit a packet.
  const bool lanes = packetPathEnabled() && integrator.samples <= kMaxPacketDraws;
  const PacketCamera packetCamera = makePacketCamera(camera, *filter);
  auto plan = std::make_shared<const DrawPlan>(drawPlan({DrawRequests{1, integrator.samples}}));
  const int laneCount = std::min(packetLanes(), kMaxPacketLanes);
  const PacketKernels& kernels = packetKernels();
  // One per row renderer, i.e. per worker thread; reused row after row.
  struct Batch {
    Batch(const SceneGeometry& geometry, size_t drawCount)
        : rays(geometry), drawBuffer(drawCount), draws(drawBuffer.draws()) {}
    OcclusionBatch rays;
    std::vector<float> contribution;  // of each ray
    std::vector<uint32_t> firstRay;   // of each pixel, and one past the last pixel's rays
    std::vector<float> weight;        // each pixel's filter weight
    // One packet of camera samples.
    PacketStreamStart start;
    float filterU[2][kMaxPacketLanes];
    PacketDrawBuffer drawBuffer;
    PacketDraws draws;
    PacketRays cameraRays;
    float cameraWeight[kMaxPacketLanes];
  };
  auto batch = std::make_shared<Batch>(scene->geometry, lanes ? size_t(integrator.samples) : 0);
  RowRenderer r;
  r.row = [camera, filter, scene, integrator, batch, lanes, packetCamera, plan, laneCount, kernels](
              int y, uint32_t pass, Sampler& sampler, Film& film, uint64_t& badSamples,
              const std::atomic<bool>& cancel) {
    Batch& b = *batch;
    const int width = camera.width();
    const int pixels = std::max(1, kAoBatchRays / std::max(1, integrator.samples));
    // Queues pixel x's visibility rays (`draws`: the sampler after its filter draw, or its lane's
    // draws).
    auto queuePixel = [&](const Ray& ray, float weight, auto& draws) {
      b.weight.push_back(weight);
      b.firstRay.push_back(uint32_t(b.rays.size()));
      integrator.forEachVisibilityRay(*scene, ray, draws, [&](const Ray& shadow, float contribution) {
        b.rays.add(shadow);
        b.contribution.push_back(contribution);
      });
    };
    const PacketDrawPlan draws = plan->view();
    if (lanes) startPacketStreamRow(sampler, pass, b.start);
    for (int x0 = 0; x0 < width; x0 += pixels) {
      if (cancel.load(std::memory_order_relaxed)) return;
      const int x1 = std::min(width, x0 + pixels);
      b.rays.clear();
      b.contribution.clear();
      b.firstRay.clear();
      b.weight.clear();
      if (lanes) {
        for (int x = x0; x < x1; x += laneCount) {
          const int count = std::min(laneCount, x1 - x);
          startPacketStreams(x, y, count, laneCount, b.start);
          kernels.samplerDraws(b.start, draws, b.filterU, b.draws);
          kernels.cameraRays(packetCamera, x, y, count, b.filterU, b.cameraRays, b.cameraWeight);
          for (int k = 0; k < count; ++k) {
            PacketLaneDraws laneDraws{b.draws, k};
            queuePixel(cameraRay(b.cameraRays, k), b.cameraWeight[k], laneDraws);
          }
        }
      } else {
        for (int x = x0; x < x1; ++x) {
          float weight;
          const Ray ray = startCameraSample(camera, *filter, sampler, x, y, pass, weight);
          queuePixel(ray, weight, sampler);
        }
      }
      b.firstRay.push_back(uint32_t(b.rays.size()));
      b.rays.trace();
      for (int x = x0; x < x1; ++x) {
        const size_t i = size_t(x - x0);
        float sum = 0.f;
        for (uint32_t k = b.firstRay[i]; k < b.firstRay[i + 1]; ++k)
          if (!b.rays.occluded(k)) sum += b.contribution[k];
        const Color3 L = integrator.radiance(sum);
        // NaN, Inf or negative radiance is a bug somewhere: count it and add nothing.
        if (isValidRadiance(L))
          film.add(x, y, L * b.weight[i]);
        else
          ++badSamples;
      }
    }
  };
  r.preview = [camera, scene, integrator](int y0, int block, Sampler& sampler, Image& image,
                                          const std::atomic<bool>& cancel) {
    previewBlocks(camera, *scene, integrator, y0, block, sampler, image, cancel);
  };
  return r;
}

}  // namespace penumbra
