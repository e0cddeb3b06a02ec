// One image row of one pass: per pixel, restart the sample stream, importance-sample the pixel
// filter, trace the camera ray through the integrator and accumulate. The integrator and its
// strategy are template parameters (core/render/row_loop.h), chosen once per render through the
// strategy table (no per-sample dispatch).
#pragma once

#include <cstdint>
#include <functional>

#include "core/render/engine.h"

namespace penumbra {

struct RowRenderer {
  // Row y of pass `pass` into the film.
  std::function<void(int y, uint32_t pass, Sampler& sampler, Film& film, uint64_t& badSamples)> row;
  // A preview of the rows [y, y + block): one sample (index 0) per block x block square, written to
  // every pixel of the square in `image`.
  std::function<void(int y, int block, Sampler& sampler, Image& image)> preview;
};

RowRenderer makeRowRenderer(const RenderJob& job);

}  // namespace penumbra
