// Which estimator renders the image, with its settings. Plain data: the viewer edits it live and the
// row renderer resolves it to one concrete integrator type per render (no per-sample dispatch).
#pragma once

#include <cstdint>

namespace penumbra {

// Every way of rendering an image: an integrator with its sampling strategy. Names, XML spellings,
// when each applies and how it is instantiated: one row each in core/render/strategy_table.h.
enum class Strategy : uint8_t {
  DirectUniformHemisphere,    // direct light by uniform hemisphere directions
  DirectCosineHemisphere,     // direct light by cosine-weighted hemisphere directions
  DirectArea,                 // direct light by uniform points on each light sphere
  DirectAreaUniform,          // ... on one light per sample, chosen uniformly
  DirectAreaPower,            // ... on one light per sample, chosen by emitted power
  DirectAreaBvh,              // ... on one light per sample, chosen by the light BVH
  DirectSolidAngle,           // direct light by uniform directions in each light's cone
  DirectSolidAngleUniform,    // ... of one light per sample, chosen uniformly
  DirectSolidAnglePower,      // ... of one light per sample, chosen by emitted power
  DirectSolidAngleBvh,        // ... of one light per sample, chosen by the light BVH
  DirectProjectedSolidAngle,  // direct light by directions in each light's cone with density ∝ cos θ
  DirectProjectedSolidAngleUniform,  // ... of one light per sample, chosen uniformly
  DirectProjectedSolidAnglePower,    // ... of one light per sample, chosen by emitted power
  DirectProjectedSolidAngleBvh,      // ... of one light per sample, chosen by the light BVH
  DirectMisSolidAnglePower,  // MIS of solid-angle light sampling and cosine directions, power heuristic
  DirectMisSolidAngleBalance,
  DirectMisAreaPower,  // MIS of area light sampling and cosine directions
  DirectMisAreaBalance,
  DirectMisProjectedPower,  // MIS of projected-solid-angle light sampling and cosine directions
  DirectMisProjectedBalance,
  AoUniform,  // ambient occlusion by uniform hemisphere directions
  AoCosine,   // ambient occlusion by cosine-weighted directions
  Simple,     // point and directional lights only
  Normals,    // the shading normal as a colour
};
inline constexpr int kStrategyCount = 24;

// How a light-sampling strategy of `direct` chooses the sphere lights it samples: every light for
// every shading sample (All), or one per shading sample (core/lights/light_selection.h). The mis rows
// always sample every light (core/integrators/mis_integrator.h says why).
enum class LightSelection : uint8_t { All, Uniform, Power, Bvh };

constexpr LightSelection lightSelectionOf(Strategy s) {
  switch (s) {
    case Strategy::DirectAreaUniform:
    case Strategy::DirectSolidAngleUniform:
    case Strategy::DirectProjectedSolidAngleUniform:
      return LightSelection::Uniform;
    case Strategy::DirectAreaPower:
    case Strategy::DirectSolidAnglePower:
    case Strategy::DirectProjectedSolidAnglePower:
      return LightSelection::Power;
    case Strategy::DirectAreaBvh:
    case Strategy::DirectSolidAngleBvh:
    case Strategy::DirectProjectedSolidAngleBvh:
      return LightSelection::Bvh;
    default:
      return LightSelection::All;
  }
}
// Whether s samples points uniformly on the light spheres (any light selection; not the mis rows).
constexpr bool samplesLightArea(Strategy s) {
  return s == Strategy::DirectArea || s == Strategy::DirectAreaUniform || s == Strategy::DirectAreaPower ||
         s == Strategy::DirectAreaBvh;
}
// Whether s samples directions uniformly in the lights' cones (any light selection; not the mis rows).
constexpr bool samplesLightSolidAngle(Strategy s) {
  return s == Strategy::DirectSolidAngle || s == Strategy::DirectSolidAngleUniform ||
         s == Strategy::DirectSolidAnglePower || s == Strategy::DirectSolidAngleBvh;
}
// Whether s samples directions in the lights' cones in proportion to cos θ (any light selection; not
// the mis rows).
constexpr bool samplesLightProjectedSolidAngle(Strategy s) {
  return s == Strategy::DirectProjectedSolidAngle || s == Strategy::DirectProjectedSolidAngleUniform ||
         s == Strategy::DirectProjectedSolidAnglePower || s == Strategy::DirectProjectedSolidAngleBvh;
}

struct IntegratorDesc {
  Strategy strategy = Strategy::DirectSolidAngle;
  int samples = 1;  // shading samples per camera sample (ao: shadingSamples, direct: nSamples)
  // The MIS strategies' counts per camera sample: light-sampling directions per sphere light, and
  // cosine-hemisphere directions shared by all lights (0 turns MIS into the other technique alone).
  int lightSamples = 1;
  int bsdfSamples = 1;

  bool operator==(const IntegratorDesc&) const = default;
};

}  // namespace penumbra
