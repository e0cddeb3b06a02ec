// Error against run time (or samples) for one strategy from a cold start.
//
// The engine renders on all cores with a time (or spp) limit, measured at a log-spaced set of
// targets. Time mode: a polling loop asks for a snapshot when the elapsed rendering time crosses the
// next target; the snapshot is published at the next pass boundary and carries that boundary's exact
// spp and seconds, which are what gets recorded (never the target). Snapshot resolution runs inside
// the timed region, so the times include the measurement's own small overhead, as a user would see it.
// Spp mode: the render stops at each target spp, its film is measured, and it is extended to the next
// (Engine::extend), so the points are the targets whatever the machine's load.
// The metrics are computed on the polling thread against the reference.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/analysis/error_metrics.h"
#include "core/analysis/reference.h"
#include "core/analysis/strategy_lists.h"
#include "core/math/cancellation.h"

namespace penumbra {

struct ConvergencePoint {
  double seconds = 0;  // wall-clock rendering time (pauses excluded)
  // CPU time the render used (process CPU since start minus this polling thread's own CPU, which
  // computes the metrics): immune to other processes competing for the cores.
  double cpuSeconds = 0;
  uint32_t spp = 0;
  uint64_t samples = 0;  // camera samples (spp * pixels)
  ErrorReport error;
};

struct ConvergenceRun {
  std::string strategy;  // strategyLabel
  IntegratorDesc integrator;
  SamplerKind sampler = SamplerKind::Independent;
  std::vector<ConvergencePoint> points;
  Image finalImage;  // the mean at the end (equal time or equal spp across strategies)
  double seconds = 0;
  uint32_t spp = 0;
};

struct ConvergenceOptions {
  double seconds = 0;  // time mode: render this long (ignored when spp > 0)
  uint32_t spp = 0;    // spp mode: render this many passes
  int threads = 0;     // 0: all cores
  uint64_t seed = 0;
  int pointsPerDecade = 6;
  double firstFraction = 1e-3;  // first target = firstFraction * limit (time mode)
  CancelFlag cancel = nullptr;  // set: the run stops within milliseconds and throws Cancelled
};

// The scene's samplers, or those named in `list` (comma separated sampler names, or "all" for every
// row of the sampler table). Throws Error.
std::vector<SamplerKind> parseSamplers(SamplerKind sceneSampler, const std::string& list);
ConvergenceRun runConvergence(const LoadedScene& scene, const IntegratorDesc& strategy, SamplerKind sampler,
                              const Reference& ref, const std::vector<uint8_t>& seesLight,
                              const ConvergenceOptions& options);
// With the scene's sampler.
ConvergenceRun runConvergence(const LoadedScene& scene, const IntegratorDesc& strategy, const Reference& ref,
                              const std::vector<uint8_t>& seesLight, const ConvergenceOptions& options);

// Efficiency 1 / (MSE * seconds) of a run, from the geometric mean of MSE * seconds over the points of
// its last decade of time (MSE * t is constant for an unbiased estimator; averaging several points
// damps the noise of a single one). noLight selects the metric over pixels that see no light.
// cpuTime: use ConvergencePoint::cpuSeconds instead of wall seconds.
double efficiency(const ConvergenceRun& run, bool noLight = false, bool cpuTime = false);
// Least-squares slope of log MSE against log time (cpuTime: CPU seconds; spp mode: pass spp) over
// the run's points from its fourth pass on (the first passes are mostly start-up): -1 for
// independent samples, steeper where a sampler's nets pay off. NaN with fewer than 3 points.
double mseSlope(const ConvergenceRun& run, bool sppAxis, bool noLight = false, bool cpuTime = false);

}  // namespace penumbra
