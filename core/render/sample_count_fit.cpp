#include "core/render/sample_count_fit.h"

#include "core/sampling/sampler_table.h"

namespace penumbra {

std::string fitSampleCountToTarget(RenderSettings& s, uint32_t targetSpp) {
  const SampleCountRule fit = samplerRow(s.samplerKind).fitSampleCount;
  if (!fit) return {};
  SampleCountFit f = fit(s.sampleCount, targetSpp);
  s.sampleCount = f.sampleCount;
  return f.note;
}

}  // namespace penumbra
