#include "core/render/row_renderer.h"

#include "core/integrators/ao_integrator.h"
#include "core/integrators/direct_integrator.h"
#include "core/integrators/mis_integrator.h"
#include "core/integrators/mis_light_share.h"
#include "core/integrators/normals_integrator.h"
#include "core/render/ao_batch_row_loop.h"
#include "core/render/packet_kernels.h"
#include "core/render/packet_row_loop.h"
#include "core/render/packet_scene.h"
#include "core/render/ray_estimator.h"
#include "core/render/row_loop.h"
#include "core/render/strategy_axes.h"
#include "core/render/strategy_dispatch.h"

namespace penumbra {

namespace {

// f(std::integral_constant<value>) for the row of `table` whose `field` equals `value`: a chain of
// comparisons, expanded over the table's rows at compile time, so a value added to a table is
// dispatched without a case of its own.
template <const auto& kTable, auto kField, size_t I = 0, class Value, class F>
decltype(auto) withValueOf(Value value, F&& f) {
  constexpr Value kValue = kTable[I].*kField;
  if constexpr (I + 1 == kTable.size())
    return f(std::integral_constant<Value, kValue>{});
  else if (value == kValue)
    return f(std::integral_constant<Value, kValue>{});
  else
    return withValueOf<kTable, kField, I + 1>(value, std::forward<F>(f));
}

template <class F>
decltype(auto) withWarp(HemisphereWarp v, F&& f) {
  return withValueOf<kWarps, &WarpRow::warp>(v, std::forward<F>(f));
}
template <class F>
decltype(auto) withLightMeasure(LightMeasure v, F&& f) {
  return withValueOf<kLightMeasures, &LightMeasureRow::measure>(v, std::forward<F>(f));
}
template <class F>
decltype(auto) withLightSelection(LightSelection v, F&& f) {
  return withValueOf<kLightSelections, &LightSelectionRow::selection>(v, std::forward<F>(f));
}
template <class F>
decltype(auto) withHeuristic(MisHeuristic v, F&& f) {
  return withValueOf<kHeuristics, &HeuristicRow::heuristic>(v, std::forward<F>(f));
}

template <LightMeasure kMeasure, MisHeuristic kHeuristic>
MisLightShareIntegrator<kMeasure, kHeuristic> lightShareOf(const MisIntegrator<kMeasure, kHeuristic>& mis) {
  return {mis};
}

// f(the MIS integrator of d's light measure and heuristic, with d's counts).
template <class F>
decltype(auto) withMisIntegrator(const IntegratorDesc& d, F&& f) {
  return withLightMeasure(d.lightMeasure, [&](auto m) {
    return withHeuristic(d.heuristic, [&](auto h) {
      return f(MisIntegrator<decltype(m)::value, decltype(h)::value>{d.lightSamples, d.bsdfSamples});
    });
  });
}

// f(d's integrator).
template <class F>
decltype(auto) withIntegrator(const IntegratorDesc& d, F&& f) {
  switch (d.type) {
    case IntegratorType::Ao:
      return withWarp(d.warp, [&](auto w) { return f(AoIntegrator<decltype(w)::value>{d.samples}); });
    case IntegratorType::Simple:
      return f(SimpleIntegrator{});
    case IntegratorType::Normals:
      return f(NormalsIntegrator{});
    case IntegratorType::Direct:
      break;
  }
  switch (d.estimator) {
    case Estimator::Hemisphere:
      return withWarp(d.warp,
                      [&](auto w) { return f(HemisphereDirectIntegrator<decltype(w)::value>{d.samples}); });
    case Estimator::Bsdf:
      return f(BsdfDirectIntegrator{d.samples});
    case Estimator::Light:
      return withLightMeasure(d.lightMeasure, [&](auto m) {
        return withLightSelection(d.lightSelection, [&](auto s) {
          return f(LightDirectIntegrator<decltype(m)::value, decltype(s)::value>{d.samples});
        });
      });
    case Estimator::Mis:
      break;
  }
  return withMisIntegrator(d, std::forward<F>(f));
}

}  // namespace

RowRenderer makeRowRenderer(const RenderJob& job) {
  const IntegratorDesc& d = job.settings.integrator;
  if (d.type == IntegratorType::Ao && job.scene->geometry.usesEmbree())
    return withWarp(d.warp,
                    [&](auto w) { return aoBatchRowsFor(job, AoIntegrator<decltype(w)::value>{d.samples}); });
  if (packetPathEnabled() && packetUnsupportedReason(job).empty())
    return packetRowsFor(job, makeScalarRowRenderer(job));
  return makeScalarRowRenderer(job);
}

std::string rowLoopSummary(const RenderJob& job) {
  if (job.settings.integrator.type == IntegratorType::Ao && job.scene->geometry.usesEmbree())
    return "ambient occlusion rays in batches of " + std::to_string(kAoBatchRays);
  const std::string reason = packetPathEnabled() ? packetUnsupportedReason(job) : "PENUMBRA_SIMD=off";
  if (reason.empty())
    return "packets of " + std::to_string(packetLanes()) + " camera samples (" + packetTargetName() + ")" +
           (packetGeometryQueried(*job.scene) ? ", rays sent to Embree as streams" : "");
  return "one camera sample at a time: " + reason;
}

RowRenderer makeScalarRowRenderer(const RenderJob& job) {
  const IntegratorDesc& d = job.settings.integrator;
  // A light-share job of a strategy without that output renders radiance (callers check offersLightShare).
  if (job.output == RenderOutput::MisLightShare && offersLightShare(d))
    return withMisIntegrator(d, [&](auto mis) { return rowsFor(job, lightShareOf(mis)); });
  return withIntegrator(d, [&](auto integrator) { return rowsFor(job, integrator); });
}

RayEstimate estimateRayOf(const IntegratorDesc& desc, const Scene& scene, const Ray& ray, int n,
                          uint64_t seed, SamplerKind sampler) {
  IntegratorDesc d = desc;
  d.lightSamples = d.bsdfSamples = d.samples;
  return withIntegrator(
      d, [&](auto integrator) { return estimateRay(scene, integrator, ray, n, seed, sampler); });
}

}  // namespace penumbra
