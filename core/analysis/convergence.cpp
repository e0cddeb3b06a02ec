#include "core/analysis/convergence.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <thread>

#include "core/math/error.h"
#include "core/render/cpu_clock.h"
#include "core/render/engine.h"
#include "core/sampling/sampler_table.h"

namespace penumbra {

std::vector<SamplerKind> parseSamplers(SamplerKind sceneSampler, const std::string& list) {
  if (list.empty()) return {sceneSampler};
  std::vector<SamplerKind> out;
  if (list == "all") {
    for (const SamplerRow& r : samplerTable()) out.push_back(r.kind);
    return out;
  }
  std::stringstream ss(list);
  for (std::string name; std::getline(ss, name, ',');) {
    SamplerKind k;
    if (!parseSamplerKind(name, k))
      throw Error("converge: unknown sampler '" + name +
                  "' (expected all, or some of: " + acceptedSamplerNames() + ")");
    if (std::find(out.begin(), out.end(), k) == out.end()) out.push_back(k);
  }
  if (out.empty()) throw Error("converge: --samplers names no sampler");
  return out;
}

ConvergenceRun runConvergence(const LoadedScene& scene, const IntegratorDesc& strategy, const Reference& ref,
                              const std::vector<uint8_t>& seesLight, const ConvergenceOptions& o) {
  return runConvergence(scene, strategy, scene.settings.samplerKind, ref, seesLight, o);
}

ConvergenceRun runConvergence(const LoadedScene& scene, const IntegratorDesc& strategy, SamplerKind sampler,
                              const Reference& ref, const std::vector<uint8_t>& seesLight,
                              const ConvergenceOptions& o) {
  bool sppMode = o.spp > 0;
  if (!sppMode && !(o.seconds > 0)) throw Error("converge: give a time or an spp count");
  RenderSettings settings = scene.settings;
  settings.integrator = strategy;
  settings.samplerKind = sampler;
  settings.seed = o.seed;
  RenderLimits limits;
  if (sppMode)
    limits.targetSpp = o.spp;
  else
    limits.seconds = o.seconds;
  // A known final count shapes stratified's strata and zsobol's nets (as `render --spp` does).
  const auto job = std::make_shared<const RenderJob>(scene.scene, settings, limits);
  const uint64_t pixels = uint64_t(job->settings.camera.width) * uint64_t(job->settings.camera.height);

  // Log-spaced targets (seconds or spp), the last one being the limit itself.
  std::vector<double> targets;
  double limit = sppMode ? double(o.spp) : o.seconds;
  double first = sppMode ? 1.0 : limit * o.firstFraction;
  int n = std::max(1, int(std::ceil(std::log10(limit / first) * o.pointsPerDecade)));
  for (int k = 0; k <= n; ++k) {
    double t = first * std::pow(limit / first, double(k) / n);
    if (sppMode) t = std::round(t);
    if (targets.empty() || t > targets.back()) targets.push_back(t);
  }
  targets.pop_back();  // the final point comes from the film after the render stops

  ConvergenceRun run;
  run.strategy = strategyLabel(strategy);
  run.integrator = strategy;
  run.sampler = sampler;
  // This polling thread's CPU (snapshot copies, metrics) is not part of the render's cost.
  double pollerCpuStart = 0;
  auto record = [&](const Image& mean, uint32_t spp, double seconds, double cpu) {
    ConvergencePoint p;
    p.seconds = seconds;
    p.cpuSeconds = cpu - (threadCpuSeconds() - pollerCpuStart);
    p.spp = spp;
    p.samples = uint64_t(spp) * pixels;
    p.error = computeErrors(mean, ref.mean, ref.standardError, seesLight);
    run.points.push_back(p);
  };

  Engine engine;
  double cpuStart = processCpuSeconds();
  pollerCpuStart = threadCpuSeconds();
  // Ends the render and throws Cancelled when asked to.
  auto stopIfCancelled = [&] {
    if (cancelRequested(o.cancel)) {
      engine.cancel();
      throw Cancelled();
    }
  };
  // Waits for the render to reach its limits.
  auto waitCancellable = [&] {
    while (!engine.progress().finished) {
      stopIfCancelled();
      std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
  };
  if (sppMode) {
    // Every target is a stop: the render halts at its spp, the film is measured, and the render is
    // extended to the next one. The points do not depend on how quickly this thread polls (a small
    // image renders many passes within one poll on a loaded machine).
    RenderLimits step = limits;
    for (std::size_t k = 0; k < targets.size(); ++k) {
      step.targetSpp = uint32_t(targets[k]);
      if (k == 0)
        engine.start(job, step, o.threads);
      else
        engine.extend(step);
      waitCancellable();
      engine.wait();
      const RenderProgress p = engine.progress();
      if (p.spp > 0 && (run.points.empty() || p.spp > run.points.back().spp))
        record(engine.film().mean(p.spp), p.spp, p.seconds, processCpuSeconds() - cpuStart);
    }
    if (targets.empty())
      engine.start(job, limits, o.threads);
    else
      engine.extend(limits);
    waitCancellable();
  } else {
    engine.start(job, limits, o.threads);
    std::size_t next = 0;
    bool requested = false;
    FilmSnapshot snap;
    while (true) {
      RenderProgress p = engine.progress();
      if (engine.latestSnapshot(snap) && snap.spp > 0 && !snap.mean.empty()) {
        if (run.points.empty() || snap.spp > run.points.back().spp)
          record(snap.mean, snap.spp, snap.seconds, snap.cpuSeconds);
        requested = false;
        while (next < targets.size() && targets[next] <= snap.seconds) ++next;
      }
      if (p.finished) break;
      stopIfCancelled();
      if (!requested && next < targets.size() && p.seconds >= targets[next]) {
        engine.requestSnapshot(false);
        requested = true;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
  }
  engine.wait();
  double cpuEnd = processCpuSeconds() - cpuStart;
  RenderProgress p = engine.progress();
  run.finalImage = engine.film().mean(p.spp);
  run.seconds = p.seconds;
  run.spp = p.spp;
  if (p.spp > 0 && (run.points.empty() || run.points.back().spp < p.spp))
    record(run.finalImage, p.spp, p.seconds, cpuEnd);
  return run;
}

double efficiency(const ConvergenceRun& run, bool noLight, bool cpuTime) {
  if (run.points.empty()) return 0;
  double tEnd = run.points.back().seconds;
  double sumLog = 0;
  int n = 0;
  for (const ConvergencePoint& p : run.points) {
    if (p.seconds < tEnd / 10) continue;
    double mse = noLight ? p.error.noLight.mse : p.error.all.mse;
    double t = cpuTime ? p.cpuSeconds : p.seconds;
    if (!(mse > 0) || !(t > 0)) continue;
    sumLog += std::log(mse * t);
    ++n;
  }
  if (n == 0) return 0;
  return 1.0 / std::exp(sumLog / n);
}

}  // namespace penumbra

namespace penumbra {

double mseSlope(const ConvergenceRun& run, bool sppAxis, bool noLight, bool cpuTime) {
  std::vector<double> x, y;
  for (const ConvergencePoint& p : run.points) {
    double t = sppAxis ? double(p.spp) : cpuTime ? p.cpuSeconds : p.seconds;
    double mse = noLight ? p.error.noLight.mse : p.error.all.mse;
    if (p.spp < 4 || !(t > 0) || !(mse > 0)) continue;
    x.push_back(std::log(t));
    y.push_back(std::log(mse));
  }
  if (x.size() < 3) return NAN;
  double mx = 0, my = 0;
  for (size_t i = 0; i < x.size(); ++i) mx += x[i], my += y[i];
  mx /= double(x.size()), my /= double(y.size());
  double sxy = 0, sxx = 0;
  for (size_t i = 0; i < x.size(); ++i) sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx);
  return sxx > 0 ? sxy / sxx : NAN;
}

}  // namespace penumbra
