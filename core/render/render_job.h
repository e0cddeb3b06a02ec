// What one accumulation renders (the job) and when it stops (the limits): shared by the engine,
// which schedules passes, and the row renderer, which renders them.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "core/render/render_settings.h"
#include "core/world/scene.h"

namespace penumbra {

// What the film accumulates per camera sample: the radiance estimate, or (MIS only) its parts by
// technique, for the viewer's light-share view (core/integrators/mis_light_share.h).
enum class RenderOutput : uint8_t { Radiance, MisLightShare };

struct RenderLimits {
  uint32_t targetSpp = 0;  // 0: no limit
  double seconds = 0.0;    // 0: no limit; checked at pass boundaries
  // Before the first pass, render one sample per kPreviewBlock^2 block and publish it (upscaled) as
  // a snapshot with spp 0, so an interactive view shows the new estimate within milliseconds.
  bool preview = false;
};

inline constexpr int kPreviewBlock = 4;

struct RenderJob {
  // The job of a run with these limits: `settings` with the sampler's sampleCount fitted to the
  // run's final count, limits.targetSpp (0: not known; a time limit alone does not know it), by the
  // sampler's row (SamplerRow::fitSampleCount, core/sampling/sampler_table.h). Every job is made
  // from settings and limits here, so every front end renders the pattern the row says and can
  // show its note.
  RenderJob(std::shared_ptr<const Scene> scene, RenderSettings settings, const RenderLimits& limits,
            RenderOutput output = RenderOutput::Radiance);

  std::shared_ptr<const Scene> scene;
  RenderSettings settings;
  RenderOutput output = RenderOutput::Radiance;
  // The row's note: with the numbers, what the sampler does when the run's count cannot shape it as
  // asked (a count that does not fit its pattern, or no known final count); empty when it can, and
  // for samplers the count does not shape.
  std::string samplerNote;
};

}  // namespace penumbra
