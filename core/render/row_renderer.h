// One image row of one pass: per pixel, restart the sample stream, importance-sample the pixel
// filter, trace the camera ray through the integrator and accumulate. The integrator and its
// strategy are template parameters (core/render/row_loop.h), chosen once per render through the
// strategy axes (row_renderer.cpp: no per-sample dispatch).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "core/image/image.h"
#include "core/render/film.h"
#include "core/render/render_job.h"
#include "core/sampling/sampler.h"

namespace penumbra {

struct RowRenderer {
  // Row y of pass `pass` into the film. Stops between two pixels once *cancel is set (checked per
  // pixel, so cancelling takes one pixel's time however many samples the integrator takes; a batched
  // loop checks per batch, at most ~1,000 rays); the row is then incomplete and the pass must be
  // abandoned.
  std::function<void(int y, uint32_t pass, Sampler& sampler, Film& film, uint64_t& badSamples,
                     const std::atomic<bool>& cancel)>
      row;
  // A preview of the rows [y, y + block): one sample (index 0) per block x block square, written to
  // every pixel of the square in `image`. Stops between two squares once *cancel is set, as `row`
  // does between two pixels.
  std::function<void(int y, int block, Sampler& sampler, Image& image, const std::atomic<bool>& cancel)>
      preview;
};

// The row renderer of the job's strategy: packets of camera samples in SIMD lanes where the packet
// path supports the job (packet_row_loop.h); ambient occlusion in a scene whose triangles are in
// Embree traces its visibility rays in batches (ao_batch_row_loop.h); everything else renders one
// camera sample at a time.
RowRenderer makeRowRenderer(const RenderJob& job);
// Which of those makeRowRenderer chooses for the job, in words (e.g. "packets of 8 camera samples
// (AVX3)", or "one camera sample at a time: <why not in packets>").
std::string rowLoopSummary(const RenderJob& job);
// One camera sample at a time for every strategy: the reference the batched loops are tested against
// (the same image, bit for bit).
RowRenderer makeScalarRowRenderer(const RenderJob& job);

}  // namespace penumbra
