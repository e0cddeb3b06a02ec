// Per-pixel sample streams for the integrators. A stream is a pure function of
// (seed, pixel, sample index): images do not depend on thread count or scheduling.
// Concrete (no virtual calls): the engine owns one Sampler per worker and restarts it per pixel sample.
#pragma once

#include <cstdint>
#include <string>

#include "core/math/vec.h"

namespace penumbra {

enum class SamplerKind : uint8_t { Independent, Stratified };

const char* samplerKindName(SamplerKind kind);
// Returns false for unknown names.
bool parseSamplerKind(const std::string& name, SamplerKind& out);

class Sampler {
 public:
  // sampleCount: the scene's samples per pixel; for Stratified it is the number of strata per
  // dimension pair (rounded down to a square), repeating with fresh jitter beyond it.
  Sampler(SamplerKind kind, uint32_t sampleCount, uint64_t seed);

  // Restarts the stream for one pixel sample. Cheap: called once per camera sample.
  void startPixelSample(IVec2 pixel, uint32_t sampleIndex);

  // Uniform in [0, 1): never returns 1.0.
  float next1D();
  Vec2 next2D();

  SamplerKind kind() const;
  uint32_t sampleCount() const;
  uint64_t seed() const;
  // (implementation-defined private state follows)
};

}  // namespace penumbra
