// penumbra bench: renderer throughput, measured the way users render (whole passes, all pixels).
//   * camera samples/s for every direct-illumination strategy on the sphere scene
//   (scenes/hw2/Tests/sphere-area.xml);
//   * camera samples/s for every sampler on the same scene, at 1 thread, interleaved run by run;
//   * SIMD packets against one camera sample at a time, per strategy, at 1 thread, on the best
//     instruction set and with AVX2 forced;
//   * AO rays/s on the stand-in rock mesh (1.3 M triangles, Embree);
//   * a scaling series: 10 to 10,000 sphere lights over a floor (core/scene/scaling_scene.h), camera
//     samples/s of each light selection at a fixed spp;
// each at 1 thread and at all threads, median of several timed runs, with the threads' speed-up.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <thread>
#include <vector>

#include "app/cli/commands.h"
#include "app/cli/cpu_usage.h"
#include "app/cli/option_checks.h"
#include "app/cli/scene_options.h"
#include "core/analysis/order_statistics.h"
#include "core/image/atomic_file.h"
#include "core/math/error.h"
#include "core/render/engine.h"
#include "core/render/packet_kernels.h"
#include "core/render/packet_row_loop.h"
#include "core/render/packet_scene.h"
#include "core/render/row_renderer.h"
#include "core/sampling/sampler_table.h"
#include "core/scene/scaling_scene.h"
#include "core/scene/xml_parser.h"

namespace penumbra::cli {

namespace {

struct BenchOptions {
  std::string sphereScene;  // default: the built-in sphere scene (defaultSceneXml)
  std::string aoScene;      // default: scenes/standin/rock-ao.xml next to the executable's repo
  // Many short pairs rather than a few long ones: the two runs of a pair are closer in time (less
  // drift between them) and the median has more to go on. The figures in docs/performance.md use these
  // defaults.
  double seconds = 1.0;
  int repeats = 9;
  int threads = 0;
  int scalingSpp = 2;  // samples per pixel of each render of the scaling series (0: no series)
  bool scalingOnly = false;
  bool simdOnly = false;
  std::string writeScalingScene;  // write the scaling scene with `scalingLights` lights here and exit
  int scalingLights = 1000;
};

// One render of `spp` passes: camera samples per second.
double fixedSppRun(const LoadedScene& s, const RenderSettings& settings, int threads, uint32_t spp) {
  const RenderLimits limits{spp, 0.0};
  Engine engine;
  engine.start(std::make_shared<const RenderJob>(s.scene, settings, limits), limits, threads);
  engine.wait();
  RenderProgress p = engine.progress();
  return double(p.samples) / p.seconds;
}

// The scaling series: n sphere lights plus n non-emitting spheres over a floor, 128², every light
// selection of solid-angle sampling. `all` is skipped where one render would take minutes.
void scalingSeries(const BenchOptions& o, int threads) {
  std::printf(
      "\nscaling series: n sphere lights + n spheres over a floor, 128x128, %d spp, %d threads,\n"
      "camera samples/s (M/s) per light selection; time per sample relative to n = 100 in ()\n",
      o.scalingSpp, threads);
  std::vector<IntegratorDesc> selections;
  for (const LightSelectionRow& r : kLightSelections)
    selections.push_back(directByLight(LightMeasure::SolidAngle, r.selection));
  std::printf("%8s %8s", "lights", "BVH");
  for (const IntegratorDesc& st : selections) std::printf(" %22s", strategyLabel(st).c_str());
  std::printf("\n");
  std::vector<double> at100(selections.size(), 0.0);
  for (int n : {10, 100, 1000, 10000}) {
    LoadedScene scene = loadSceneFromString(scalingSceneXml(n, 128, o.scalingSpp), "<scaling scene>", ".");
    std::printf("%8d %8s", n, scene.scene->geometry.spheresUseBvh() ? "spheres" : "-");
    for (size_t i = 0; i < selections.size(); ++i) {
      if (selections[i].lightSelection == LightSelection::All && n > 1000) {
        std::printf(" %22s", "(skipped)");
        continue;
      }
      RenderSettings settings = scene.settings;
      settings.integrator = selections[i];
      const double rate = fixedSppRun(scene, settings, threads, uint32_t(o.scalingSpp));
      if (n == 100) at100[i] = rate;
      char cell[40];
      if (n >= 100 && at100[i] > 0)
        std::snprintf(cell, sizeof cell, "%.3f (%.2fx)", rate * 1e-6, at100[i] / rate);
      else
        std::snprintf(cell, sizeof cell, "%.3f", rate * 1e-6);
      std::printf(" %22s", cell);
      std::fflush(stdout);
    }
    std::printf("\n");
  }
}

// One timed run of `seconds`: camera samples per second. `scalar`: one camera sample at a time even
// where the renderer batches (makeScalarRowRenderer).
double timedRun(const LoadedScene& s, const RenderSettings& settings, int threads, double seconds,
                bool scalar = false) {
  const RenderLimits limits{0, seconds};
  Engine engine;
  if (scalar) engine.setRowRendererFactory(makeScalarRowRenderer);
  engine.start(std::make_shared<const RenderJob>(s.scene, settings, limits), limits, threads);
  engine.wait();
  RenderProgress p = engine.progress();
  return double(p.samples) / p.seconds;
}

// The renderer's default row loop (packets, batches) against one camera sample at a time at 1 thread,
// the two alternating run by run (which goes first alternates too): each one's median rate, and the
// median and range of the pairs' ratios.
struct AgainstScalar {
  double rate = 0, scalarRate = 0, ratio = 0, ratioMin = 0, ratioMax = 0;
};
AgainstScalar againstScalar(const LoadedScene& s, const RenderSettings& settings, const BenchOptions& o) {
  std::vector<double> rates, scalarRates, ratios;
  for (int r = 0; r < o.repeats; ++r) {
    const bool scalarFirst = r % 2 == 1;
    const double a = timedRun(s, settings, 1, o.seconds, scalarFirst);
    const double b = timedRun(s, settings, 1, o.seconds, !scalarFirst);
    const double rate = scalarFirst ? b : a, scalar = scalarFirst ? a : b;
    rates.push_back(rate);
    scalarRates.push_back(scalar);
    ratios.push_back(rate / scalar);
  }
  return {median(rates), median(scalarRates), median(ratios), *std::min_element(ratios.begin(), ratios.end()),
          *std::max_element(ratios.begin(), ratios.end())};
}

// Camera samples per second at 1 thread and at `all`, and the speed-up. The two thread counts
// alternate run by run in the order 1,N, N,1, 1,N, ... (a linear drift of the machine's speed
// cancels), and the speed-up is the median of each pair's ratio: on a shared machine whose speed
// drifts, both sides of a ratio are measured in the same seconds. The range of the ratios and how
// much CPU the runs actually got are reported beside it, so a contended figure shows as one.
struct Scaling {
  double one = 0, all = 0, speedUp = 0, speedUpMin = 0, speedUpMax = 0;
  double coresGot = 0;  // CpuShare::coresGot of the all-thread runs
  double steal = -1;    // CpuShare::steal over the whole measurement (< 0: unknown)
};
Scaling measure(const LoadedScene& s, const RenderSettings& settings, int all, const BenchOptions& o) {
  std::vector<double> one, many, ratio;
  double allWall = 0, allCpu = 0;  // seconds, summed over the all-thread runs only
  const CpuClock first = readCpuClock();
  auto run = [&](int threads) {
    const CpuClock before = readCpuClock();
    double rate = timedRun(s, settings, threads, o.seconds);
    if (threads == all) {
      const CpuClock after = readCpuClock();
      allWall += after.wallSeconds - before.wallSeconds;
      allCpu += after.processSeconds - before.processSeconds;
    }
    (threads == 1 ? one : many).push_back(rate);
  };
  for (int r = 0; r < o.repeats; ++r) {
    if (r % 2 == 0) {
      run(1);
      run(all);
    } else {
      run(all);
      run(1);
    }
    ratio.push_back(many.back() / one.back());
  }
  return {median(one),
          median(many),
          median(ratio),
          *std::min_element(ratio.begin(), ratio.end()),
          *std::max_element(ratio.begin(), ratio.end()),
          allCpu / (allWall * all),
          cpuShareBetween(first, readCpuClock(), all).steal};
}

// Width of the first column: the longest strategy label (the mis strategies', 40 characters) fits.
int labelWidth() {
  size_t w = 28;
  for (const IntegratorDesc& d : everyStrategy()) w = std::max(w, strategyLabel(d).size());
  return int(w);
}

// Every sampler at 1 thread, interleaved run by run (forward, then backward, ...), so each round's
// ratio to the first sampler is measured within seconds; the median ratio and its range.
struct SamplerFigure {
  double rate = 0, ratio = 0, ratioMin = 0, ratioMax = 0;
};
std::vector<SamplerFigure> measureSamplers(const LoadedScene& s, const BenchOptions& o) {
  const auto rows = samplerTable();
  std::vector<std::vector<double>> rates(rows.size()), ratios(rows.size());
  for (int r = 0; r < o.repeats; ++r) {
    std::vector<double> round(rows.size());
    for (size_t k = 0; k < rows.size(); ++k) {
      size_t i = r % 2 == 0 ? k : rows.size() - 1 - k;
      RenderSettings settings = s.settings;
      settings.samplerKind = rows[i].kind;
      round[i] = timedRun(s, settings, 1, o.seconds);
    }
    for (size_t i = 0; i < rows.size(); ++i) {
      rates[i].push_back(round[i]);
      ratios[i].push_back(round[i] / round[0]);
    }
  }
  std::vector<SamplerFigure> out;
  for (size_t i = 0; i < rows.size(); ++i)
    out.push_back({median(rates[i]), median(ratios[i]), *std::min_element(ratios[i].begin(), ratios[i].end()),
                   *std::max_element(ratios[i].begin(), ratios[i].end())});
  return out;
}

void printHeader(const char* what) {
  std::printf("%-*s %12s %12s %20s %9s %6s\n", labelWidth(), what, "1 thread M/s", "all threads",
              "speed-up (range)", "CPU got", "steal");
}

void printRow(const std::string& label, const Scaling& m, double scale) {
  char range[32];
  std::snprintf(range, sizeof range, "%.2fx (%.2f-%.2f)", m.speedUp, m.speedUpMin, m.speedUpMax);
  char steal[16] = "n/a";
  if (m.steal >= 0) std::snprintf(steal, sizeof steal, "%.1f%%", 100 * m.steal);
  std::printf("%-*s %12.2f %12.2f %20s %8.0f%% %6s\n", labelWidth(), label.c_str(), m.one * scale,
              m.all * scale, range, 100 * m.coresGot, steal);
}

// Packets against one camera sample at a time for every strategy of every integrator type on the
// sphere scene, at 1 thread, on each instruction set of `targets` (forced in turn): packet M samples/s
// and the median ratio of runs alternating packet/scalar, with its range. Strategies without a packet
// kernel say why.
void simdTable(const LoadedScene& sphere, const BenchOptions& o, const std::vector<std::string>& targets) {
  std::printf("\n%-*s", labelWidth(), "SIMD packets vs one sample at a time");
  for (const std::string& t : targets) std::printf(" %12s %20s", (t + " M/s").c_str(), "speed-up (range)");
  std::printf("\n");
  for (const IntegratorDesc& strategy : everyStrategy()) {
    RenderSettings settings = sphere.settings;
    settings.integrator = withCountsOf(strategy, sphere.settings.integrator);
    const RenderJob job(sphere.scene, settings, RenderLimits{});
    std::printf("%-*s", labelWidth(), strategyLabel(strategy).c_str());
    const std::string reason = packetUnsupportedReason(job);
    if (!reason.empty()) {
      std::printf(" scalar only: %s\n", reason.c_str());
      continue;
    }
    for (const std::string& target : targets) {
      forcePacketTarget(target);
      const AgainstScalar m = againstScalar(sphere, settings, o);
      char range[40];
      std::snprintf(range, sizeof range, "%.2fx (%.2f-%.2f)", m.ratio, m.ratioMin, m.ratioMax);
      std::printf(" %12.2f %20s", m.rate * 1e-6, range);
      std::fflush(stdout);
    }
    forcePacketTarget("auto");
    std::printf("\n");
  }
}

// The SIMD table on the best instruction set, and with AVX2 forced when the CPU has something better.
void simdSection(const LoadedScene& sphere, const BenchOptions& o) {
  if (!packetPathEnabled()) {
    std::printf("\n(SIMD packets off: PENUMBRA_SIMD=off)\n");
    return;
  }
  std::vector<std::string> targets{packetTargetName()};
  for (const std::string& t : availablePacketTargets())
    if (t == "AVX2" && targets.front() != "AVX2") targets.push_back(t);
  simdTable(sphere, o, targets);
  std::printf("(1 thread; packet and scalar runs alternate, the ratio is per pair, then the median)\n");
}

std::string locateScene(const std::string& given, const std::string& repoRelative) {
  if (!given.empty()) return given;
  // Works from the repository root and from build/.
  for (const char* prefix : {"", "../", "../../"}) {
    std::string p = std::string(prefix) + repoRelative;
    if (std::filesystem::exists(p)) return p;
  }
  return "";
}

int runBench(const BenchOptions& o) {
  if (o.scalingOnly && o.scalingSpp == 0)
    throw Error(
        "bench: --scaling-spp 0 skips the scaling series, the only thing --scaling-only runs; give "
        "--scaling-spp 1 or more");
  if (!o.writeScalingScene.empty()) {
    checkOutputPath(o.writeScalingScene);
    const std::string xml = scalingSceneXml(o.scalingLights, 128, 16);
    if (xml.size() > kMaxSceneFileBytes) {
      // Scene files grow about linearly with the lights: how many would fit, to name in the message.
      const double perLight = double(xml.size()) / o.scalingLights;
      throw Error("bench --write-scaling-scene: --lights " + std::to_string(o.scalingLights) +
                  " makes a scene file of " + std::to_string(xml.size() >> 20) + " MB, above the " +
                  std::to_string(kMaxSceneFileBytes >> 20) + " MB that penumbra reads; at most about " +
                  std::to_string(int(0.99 * double(kMaxSceneFileBytes) / perLight)) + " lights fit");
    }
    writeBytesAtomically(o.writeScalingScene, xml.data(), xml.size());
    std::printf("wrote %s (%d sphere lights, %d spheres)\n", o.writeScalingScene.c_str(), o.scalingLights,
                2 * o.scalingLights);
    return 0;
  }
  int all = o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency()));
  std::printf(
      "penumbra bench: median of %d runs of %.1f s; %d hardware threads. 1-thread and all-thread runs\n"
      "alternate (1,N, N,1, ...); speed-up: median (and range) of their pairwise ratios. CPU got: CPU\n"
      "time of the all-thread runs over wall time x threads. steal: the host's steal time over all CPU\n"
      "time while the figure was measured. Below ~97%% or above ~1%%, the figure was contended; a busy\n"
      "neighbour on the host's cores shows in neither, only as a slower 1-thread figure.\n\n",
      o.repeats, o.seconds, all);
  if (o.scalingOnly) {
    scalingSeries(o, all);
    return 0;
  }

  LoadedScene sphere = o.sphereScene.empty()
                           ? loadSceneFromString(defaultSceneXml(), "<built-in sphere scene>", ".")
                           : loadScene(o.sphereScene);
  if (o.simdOnly) {
    simdSection(sphere, o);
    return 0;
  }
  // Every strategy of the scene's integrator type (the built-in scene: direct), in table order.
  const std::string_view type = nameOf(sphere.settings.integrator.type);
  std::string header = std::string(type) + " strategy (" + std::to_string(sphere.settings.camera.width) +
                       "x" + std::to_string(sphere.settings.camera.height) + ")";
  printHeader(header.c_str());
  for (const IntegratorDesc& strategy :
       everyStrategyOfType(integratorOfType(sphere.settings.integrator.type))) {
    // One light: choosing one per sample is the same work as sampling each (the scaling series below).
    if (strategy.usesLightSelection() && strategy.lightSelection != LightSelection::All) continue;
    RenderSettings s = sphere.settings;
    s.integrator = strategy;
    Scaling m = measure(sphere, s, all, o);
    printRow(strategyLabel(s.integrator), m, 1e-6);
  }

  std::printf("\n%-28s %12s %28s\n", ("sampler (" + strategyLabel(sphere.settings.integrator) + ")").c_str(),
              "1 thread M/s", "time per sample vs first");
  std::vector<SamplerFigure> samplers = measureSamplers(sphere, o);
  for (size_t i = 0; i < samplers.size(); ++i)
    std::printf("%-28s %12.2f %15.3fx (%.3f-%.3f)\n", std::string(samplerTable()[i].label).c_str(),
                samplers[i].rate * 1e-6, 1.0 / samplers[i].ratio, 1.0 / samplers[i].ratioMax,
                1.0 / samplers[i].ratioMin);
  std::printf(
      "(runs of all samplers alternate forward and backward; ratios are per round, then the median)\n");

  simdSection(sphere, o);

  std::string aoPath = locateScene(o.aoScene, "scenes/standin/rock-ao.xml");
  if (aoPath.empty()) {
    std::printf("\n(AO benchmark skipped: scenes/standin/rock-ao.xml not found; pass --ao-scene)\n");
    if (o.scalingSpp > 0) scalingSeries(o, all);
    return 0;
  }
  LoadedScene ao = loadScene(aoPath);
  const RenderSettings& s = ao.settings;
  double rays = double(s.integrator.samples);
  std::printf("\n");
  printHeader("AO rays (shadow + camera)");
  Scaling m = measure(ao, s, all, o);
  printRow(std::to_string(ao.scene->geometry.triangleCount()) + " triangles", m, rays * 1e-6);
  std::printf("(%s, %s, %d shading samples per camera sample; AO rays/s excludes camera rays)\n",
              aoPath.c_str(), strategyLabel(s.integrator).c_str(), s.integrator.samples);
  if (ao.scene->geometry.usesEmbree()) {
    // The batched row loop (the default) against one camera sample at a time, alternating at 1 thread.
    const AgainstScalar m = againstScalar(ao, s, o);
    std::printf("AO one camera sample at a time: %.2f M rays/s at 1 thread; batched %.2fx (%.2f-%.2f)\n",
                m.scalarRate * rays * 1e-6, m.ratio, m.ratioMin, m.ratioMax);
  }
  if (o.scalingSpp > 0) scalingSeries(o, all);
  return 0;
}

}  // namespace

void addBenchCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "Measure rendering throughput (camera samples/s, AO rays/s)");
  cmd->add_option("--sphere-scene", o->sphereScene,
                  "Scene for the direct strategies (default: the built-in sphere scene)");
  cmd->add_option("--ao-scene", o->aoScene,
                  "Scene for the AO benchmark (default: scenes/standin/rock-ao.xml)");
  cmd->add_option("--seconds", o->seconds, "Length of each timed run")
      ->check(finitePositiveNumber())
      ->capture_default_str();
  cmd->add_option("--repeats", o->repeats, "Timed runs per figure (the median is reported)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "Threads for the 'all threads' column")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--scaling-spp", o->scalingSpp,
                  "Samples per pixel of each render of the many-lights scaling series (0: skip it)")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  cmd->add_flag("--scaling-only", o->scalingOnly, "Run only the scaling series");
  cmd->add_flag("--simd-only", o->simdOnly,
                "Run only the table of SIMD packets against one sample at a time");
  cmd->add_option(
      "--write-scaling-scene", o->writeScalingScene,
      "Write the scaling series' scene (--lights sphere lights, 128x128, 16 spp) to this file and exit");
  cmd->add_option("--lights", o->scalingLights, "Sphere lights of --write-scaling-scene")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  cmd->callback([o, &exitCode] { exitCode = runBench(*o); });
}

}  // namespace penumbra::cli
