// The samplers: one row each, in the order the viewer lists them. The scene builder, the XML and
// metadata writers, the viewer's sampler panel and every RenderJob (which applies a row's sample
// count rule) read this table; none keeps its own list, spelling or rule. Adding a sampler:
// docs/architecture.md, "How to add a sampler".
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "core/math/spellings.h"
#include "core/sampling/sampler.h"

namespace penumbra {

// What a sampler whose pattern the sample count shapes renders with in one run.
struct SampleCountFit {
  uint32_t sampleCount = 1;  // the count its pattern takes
  // With the numbers, what the run does when the pattern cannot be the one asked for (a count that
  // does not fit the pattern, or no known final count); empty when it is.
  std::string note;
};

// A sampler's rule for fitting its sampleCount to a run: `sceneCount` is the scene's sampleCount,
// `targetSpp` the run's final count (0: not known, as with a time limit or endless accumulation).
using SampleCountRule = SampleCountFit (*)(uint32_t sceneCount, uint32_t targetSpp);

struct SamplerRow {
  SamplerKind kind;
  Spellings name;                // <sampler type="..."> (canonical first) and --set sampler=...
  std::string_view label;        // short human name (viewer)
  std::string_view description;  // one sentence (viewer tooltip)
  // How the run's count sets the pattern, for samplers whose pattern the sample count shapes
  // (stratified's strata, zsobol's shared nets); nullptr for the others, whose sampleCount only sets
  // the default target spp. Applied where a RenderJob is made (core/render/render_job.h).
  SampleCountRule fitSampleCount;

  // The scene's sampleCount shapes the pattern (not only the target spp).
  constexpr bool usesSampleCount() const { return fitSampleCount != nullptr; }
};

std::span<const SamplerRow> samplerTable();
const SamplerRow& samplerRow(SamplerKind kind);
// The row whose name or alias is `name`; nullptr when none is.
const SamplerRow* findSampler(std::string_view name);
// "independent, stratified": every accepted spelling, for messages.
std::string acceptedSamplerNames();
// The canonical spelling, e.g. "stratified".
const char* samplerKindName(SamplerKind kind);
// Accepts every spelling of every row; false for unknown names.
bool parseSamplerKind(const std::string& name, SamplerKind& out);

}  // namespace penumbra
