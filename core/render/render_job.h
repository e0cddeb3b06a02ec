// What one accumulation renders (the job) and when it stops (the limits): shared by the engine,
// which schedules passes, and the row renderer, which renders them.
#pragma once

#include <cstdint>
#include <memory>

#include "core/render/render_settings.h"
#include "core/world/scene.h"

namespace penumbra {

// What the film accumulates per camera sample: the radiance estimate, or (mis rows only) its parts by
// technique, for the viewer's light-share view (core/integrators/mis_light_share.h).
enum class RenderOutput : uint8_t { Radiance, MisLightShare };

struct RenderJob {
  std::shared_ptr<const Scene> scene;
  RenderSettings settings;
  RenderOutput output = RenderOutput::Radiance;
};

struct RenderLimits {
  uint32_t targetSpp = 0;  // 0: no limit
  double seconds = 0.0;    // 0: no limit; checked at pass boundaries
  // Before the first pass, render one sample per kPreviewBlock^2 block and publish it (upscaled) as
  // a snapshot with spp 0, so an interactive view shows the new estimate within milliseconds.
  bool preview = false;
};

inline constexpr int kPreviewBlock = 4;

}  // namespace penumbra
