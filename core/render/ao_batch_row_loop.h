// The row loop of ambient occlusion in scenes whose geometry is in Embree's BVH: camera samples in
// batches of about kAoBatchRays visibility rays (at least one pixel), which are traced together as one stream
// (OcclusionBatch: rtcOccluded1M). The camera samples' draws, filter offsets and camera rays are made in
// SIMD packets as in the packet row loop. Each pixel's rays, their contributions and the order in which they
// are summed are those of AoIntegrator::Li, so the image equals the per-sample row loop's
// (row_loop.h) bit for bit; the batch only changes how Embree is asked. With the packets, the batch's
// camera rays also go to Embree together (SceneGeometry::intersectMany: the same hits, except where
// two surfaces overlap in one plane and either may be reported).
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

// A camera sample's shading draws, kept from its packet until its camera ray's hit is known: draw i
// of the integrator's one request of n.
struct StoredDraws {
  const Vec2* u;
  Vec2 next2D(uint32_t i, uint32_t /*n*/) const { return u[i]; }
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
    // The batch's camera samples, traced together: rays, hits and shading draws (`samples` each).
    std::vector<Ray> primaryRays;
    std::vector<SurfaceHit> primaryHits;
    std::unique_ptr<bool[]> primaryFound;
    std::vector<Vec2> shadingDraws;
  };
  auto batch = std::make_shared<Batch>(scene->geometry, lanes ? size_t(integrator.samples) : 0);
  const int batchPixels = std::max(1, kAoBatchRays / std::max(1, integrator.samples));
  batch->primaryFound.reset(new bool[size_t(batchPixels)]);
  RowRenderer r;
  r.row = [camera, filter, scene, integrator, batch, batchPixels, lanes, packetCamera, plan, laneCount,
           kernels](int y, uint32_t pass, Sampler& sampler, Film& film, uint64_t& badSamples,
                    const std::atomic<bool>& cancel) {
    Batch& b = *batch;
    const int width = camera.width();
    auto queueRay = [&](const Ray& shadow, float contribution) {
      b.rays.add(shadow);
      b.contribution.push_back(contribution);
    };
    // Queues one camera sample's visibility rays, traced alone (the sampler after its filter draw).
    auto queuePixel = [&](const Ray& ray, float weight) {
      b.weight.push_back(weight);
      b.firstRay.push_back(uint32_t(b.rays.size()));
      integrator.forEachVisibilityRay(*scene, ray, sampler, queueRay);
    };
    const PacketDrawPlan draws = plan->view();
    if (lanes) startPacketStreamRow(sampler, pass, b.start);
    for (int x0 = 0; x0 < width; x0 += batchPixels) {
      if (cancel.load(std::memory_order_relaxed)) return;
      const int x1 = std::min(width, x0 + batchPixels);
      b.rays.clear();
      b.contribution.clear();
      b.firstRay.clear();
      b.weight.clear();
      if (lanes) {
        // The packets' camera rays and draws first, then their hits as one query, then the AO rays.
        const int samples = integrator.samples;
        b.primaryRays.clear();
        b.shadingDraws.clear();
        for (int x = x0; x < x1; x += laneCount) {
          const int count = std::min(laneCount, x1 - x);
          startPacketStreams(x, y, count, laneCount, b.start);
          kernels.samplerDraws(b.start, draws, b.filterU, b.draws);
          kernels.cameraRays(packetCamera, x, y, count, b.filterU, b.cameraRays, b.cameraWeight);
          for (int k = 0; k < count; ++k) {
            b.primaryRays.push_back(cameraRay(b.cameraRays, k));
            b.weight.push_back(b.cameraWeight[k]);
            for (int i = 0; i < samples; ++i)
              b.shadingDraws.emplace_back(b.draws.draw[i].u[0][k], b.draws.draw[i].u[1][k]);
          }
        }
        b.primaryHits.resize(b.primaryRays.size());
        scene->geometry.intersectMany(b.primaryRays.data(), b.primaryRays.size(), b.primaryHits.data(),
                                      b.primaryFound.get());
        for (size_t i = 0; i < b.primaryRays.size(); ++i) {
          b.firstRay.push_back(uint32_t(b.rays.size()));
          StoredDraws stored{b.shadingDraws.data() + i * size_t(samples)};
          if (b.primaryFound[i])
            integrator.forEachVisibilityRayAt(*scene, b.primaryRays[i], b.primaryHits[i], stored, queueRay);
        }
      } else {
        for (int x = x0; x < x1; ++x) {
          float weight;
          const Ray ray = startCameraSample(camera, *filter, sampler, x, y, pass, weight);
          queuePixel(ray, weight);
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
