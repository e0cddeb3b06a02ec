// One image row of one pass: per pixel, restart the sample stream, importance-sample the pixel
// filter, trace the camera ray through the integrator and accumulate. The integrator and its
// strategy are template parameters, chosen once per render (no per-sample dispatch).
#pragma once

#include <cstdint>
#include <functional>

#include "core/render/engine.h"

namespace penumbra {

using RowRenderer =
    std::function<void(int y, uint32_t pass, Sampler& sampler, Film& film, uint64_t& badSamples)>;

RowRenderer makeRowRenderer(const RenderJob& job);

}  // namespace penumbra
