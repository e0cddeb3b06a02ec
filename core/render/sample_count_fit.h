// Samplers whose pattern depends on the sample count (their row's fitSampleCount: stratified's
// strata, zsobol's shared nets) need the run's final count up front. A run that knows it (render
// --spp, converge --spp, the viewer's target spp) gets that count; one that does not (a time limit,
// endless accumulation) keeps the scene's sampleCount, and is told what that means.
#pragma once

#include <cstdint>
#include <string>

#include "core/render/render_settings.h"

namespace penumbra {

// Applies the sampler row's rule: sets s.sampleCount for the run's final count targetSpp (0: unknown),
// and returns, with the numbers, what the run does when it cannot be what was asked for (empty when
// it is, or for samplers without a rule).
std::string fitSampleCountToTarget(RenderSettings& s, uint32_t targetSpp);

}  // namespace penumbra
