// Checks of numeric arguments that the CLI's options and the Python module share, so that both
// accept the same values and say the same words about the others.
#pragma once

#include <cmath>
#include <cstdint>

namespace penumbra {

// Seconds and other amounts that must be a real, positive number: NaN and infinity are refused (a
// render of `inf` seconds would never end; every comparison with NaN is false).
inline bool isFinitePositive(double value) {
  return std::isfinite(value) && value > 0.0;
}
inline constexpr const char* kExpectedFinitePositive = "expected a finite number > 0";

// The ranges of the counts both accept.
inline constexpr int64_t kMaxRenderSpp = int64_t(1) << 30;    // render --spp, Scene.render(spp=)
inline constexpr int64_t kMaxConvergeSpp = int64_t(1) << 24;  // converge --spp, converge(spp=)
inline constexpr int kMaxThreads = 1024;                      // --threads, threads=
inline constexpr int64_t kMinChi2Samples = 100, kMaxChi2Samples = 1'000'000'000;  // warp --samples
inline constexpr int kMinChi2Resolution = 2, kMaxChi2Resolution = 1000;           // warp --res

}  // namespace penumbra
