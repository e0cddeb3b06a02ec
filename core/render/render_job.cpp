#include "core/render/render_job.h"

#include <utility>

namespace penumbra {

RenderJob::RenderJob(std::shared_ptr<const Scene> builtScene, RenderSettings asked,
                     const RenderLimits& limits, RenderOutput what)
    : scene(std::move(builtScene)), settings(std::move(asked)), output(what) {
  if (SampleCountRule fit = samplerRow(settings.samplerKind).fitSampleCount) {
    SampleCountFit f = fit(settings.sampleCount, limits.targetSpp);
    settings.sampleCount = f.sampleCount;
    samplerNote = std::move(f.note);
  }
}

}  // namespace penumbra
