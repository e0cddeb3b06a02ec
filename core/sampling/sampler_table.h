// The samplers: one row each, in the order the viewer lists them. The scene builder, the XML and
// metadata writers and the viewer's sampler panel read this table; none keeps its own list or
// spelling. Adding a sampler: docs/architecture.md, "How to add a sampler".
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "core/math/spellings.h"
#include "core/sampling/sampler.h"

namespace penumbra {

struct SamplerRow {
  SamplerKind kind;
  Spellings name;                // <sampler type="..."> (canonical first) and --set sampler=...
  std::string_view label;        // short human name (viewer)
  std::string_view description;  // one sentence (viewer tooltip)
  bool usesSampleCount;          // the scene's sampleCount shapes the pattern (not only the target spp)
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
