// Which estimator renders the image, with its settings. Plain data: the viewer edits it live and the
// row renderer resolves it to one concrete integrator type per render (no per-sample dispatch).
#pragma once

#include <cstdint>

namespace penumbra {

// Every way of rendering an image: an integrator with its sampling strategy. Names, XML spellings,
// when each applies and how it is instantiated: one row each in core/render/strategy_table.h.
enum class Strategy : uint8_t {
  DirectUniformHemisphere,  // direct light by uniform hemisphere directions
  DirectCosineHemisphere,   // direct light by cosine-weighted hemisphere directions
  DirectArea,               // direct light by uniform points on each light sphere
  DirectSolidAngle,         // direct light by uniform directions in each light's cone
  AoUniform,                // ambient occlusion by uniform hemisphere directions
  AoCosine,                 // ambient occlusion by cosine-weighted directions
  Simple,                   // point and directional lights only
  Normals,                  // the shading normal as a colour
};
inline constexpr int kStrategyCount = 8;

struct IntegratorDesc {
  Strategy strategy = Strategy::DirectSolidAngle;
  int samples = 1;  // shading samples per camera sample (ao: shadingSamples, direct: nSamples)

  bool operator==(const IntegratorDesc&) const = default;
};

}  // namespace penumbra
