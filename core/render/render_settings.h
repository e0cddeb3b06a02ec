// Everything that decides the estimate besides the scene's geometry and lights: camera, pixel filter,
// sampler and integrator. Editing these restarts accumulation but never rebuilds geometry.
#pragma once

#include <cstdint>

#include "core/integrators/integrator_desc.h"
#include "core/render/camera.h"
#include "core/render/filter.h"
#include "core/render/strategy_axes.h"
#include "core/sampling/sampler_table.h"

namespace penumbra {

struct RenderSettings {
  CameraDesc camera;
  FilterDesc filter;
  SamplerKind samplerKind = SamplerKind::Independent;
  uint32_t sampleCount = 1;  // the scene's samples per pixel (the default target)
  uint64_t seed = 0;
  IntegratorDesc integrator;
};

}  // namespace penumbra

#include <string>
#include <utility>
#include <vector>

namespace penumbra {

// Key/value description of the settings, for image metadata and logs: the integrator and its
// properties as the scene file spells them (canonical spellings of the strategy axes), sampler,
// sampleCount, seed, filter, resolution.
std::vector<std::pair<std::string, std::string>> describeSettings(const RenderSettings& s);

}  // namespace penumbra
