// Multiple-importance-sampling weights (Veach's thesis, ch. 9, the multi-sample model).
#pragma once

#include "core/integrators/integrator_desc.h"

namespace penumbra {

// Weight of technique A for a sample that A (nA samples of density pA) and B (nB samples of density
// pB) could both have produced, from a = nA·pA and b = nB·pB: balance a / (a + b), power (β = 2)
// a² / (a² + b²). Written as 1 / (1 + r), r = b / a (squared for power), so no density overflows and
// b = 0 gives exactly 1 (MIS with no samples of B is then exactly technique A alone). a > 0.
template <MisHeuristic kHeuristic>
inline float misWeight(float a, float b) {
  const float r = b / a;
  if constexpr (kHeuristic == MisHeuristic::Balance)
    return 1.f / (1.f + r);
  else
    return 1.f / (1.f + r * r);
}

}  // namespace penumbra
