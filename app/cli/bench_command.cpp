// penumbra bench: renderer throughput, measured the way users render (whole passes, all pixels).
//   * camera samples/s for every direct-illumination strategy on the hw2 sphere scene;
//   * AO rays/s on the stand-in rock mesh (1.3 M triangles, Embree);
// each at 1 thread and at all threads, median of several timed runs, with the threads' speed-up.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <thread>
#include <vector>

#include "app/cli/commands.h"
#include "app/cli/scene_options.h"
#include "core/render/engine.h"

namespace penumbra::cli {

namespace {

struct BenchOptions {
  std::string sphereScene;  // default: the built-in copy of hw2 sphere-area.xml
  std::string aoScene;      // default: scenes/standin/rock-ao.xml next to the executable's repo
  double seconds = 1.5;
  int repeats = 3;
  int threads = 0;
};

// One timed run of `seconds`: camera samples per second.
double timedRun(const LoadedScene& s, const RenderSettings& settings, int threads, double seconds) {
  auto job = std::make_shared<RenderJob>();
  job->scene = s.scene;
  job->settings = settings;
  Engine engine;
  engine.start(job, RenderLimits{0, seconds}, threads);
  engine.wait();
  RenderProgress p = engine.progress();
  return double(p.samples) / p.seconds;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Camera samples per second at 1 thread and at `all`, and the speed-up. The two thread counts
// alternate run by run, and the speed-up is the median of each pair's ratio: on a shared machine
// whose speed drifts, both sides of a ratio are measured in the same seconds.
struct Scaling {
  double one = 0, all = 0, speedUp = 0;
};
Scaling measure(const LoadedScene& s, const RenderSettings& settings, int all, const BenchOptions& o) {
  std::vector<double> one, many, ratio;
  for (int r = 0; r < o.repeats; ++r) {
    one.push_back(timedRun(s, settings, 1, o.seconds));
    many.push_back(timedRun(s, settings, all, o.seconds));
    ratio.push_back(many.back() / one.back());
  }
  return {median(one), median(many), median(ratio)};
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
  int all = o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency()));
  std::printf(
      "penumbra bench: median of %d runs of %.1f s; %d hardware threads; 1-thread and all-thread runs\n"
      "alternate, the speed-up is the median of their pairwise ratios\n\n",
      o.repeats, o.seconds, all);

  LoadedScene sphere = o.sphereScene.empty()
                           ? loadSceneFromString(defaultSceneXml(), "<built-in hw2 sphere>", ".")
                           : loadScene(o.sphereScene);
  std::printf("%-28s %14s %14s %9s\n", "direct strategy (768x768)", "1 thread M/s", "all threads",
              "speed-up");
  struct Strategy {
    DirectMeasure measure;
    HemisphereWarp warp;
  };
  for (Strategy st : {Strategy{DirectMeasure::Hemisphere, HemisphereWarp::Uniform},
                      Strategy{DirectMeasure::Hemisphere, HemisphereWarp::Cosine},
                      Strategy{DirectMeasure::Area, HemisphereWarp::Cosine},
                      Strategy{DirectMeasure::SolidAngle, HemisphereWarp::Cosine}}) {
    RenderSettings s = sphere.settings;
    s.integrator.type = IntegratorType::Direct;
    s.integrator.samples = 1;
    s.integrator.measure = st.measure;
    s.integrator.warp = st.warp;
    Scaling m = measure(sphere, s, all, o);
    std::printf("%-28s %14.2f %14.2f %8.2fx\n", strategyLabel(s.integrator).c_str(), m.one * 1e-6,
                m.all * 1e-6, m.speedUp);
  }

  std::string aoPath = locateScene(o.aoScene, "scenes/standin/rock-ao.xml");
  if (aoPath.empty()) {
    std::printf("\n(AO benchmark skipped: scenes/standin/rock-ao.xml not found; pass --ao-scene)\n");
    return 0;
  }
  LoadedScene ao = loadScene(aoPath);
  const RenderSettings& s = ao.settings;
  double rays = double(s.integrator.samples);
  std::printf("\n%-28s %14s %14s %9s\n", "AO rays (shadow + camera)", "1 thread M/s", "all threads",
              "speed-up");
  Scaling m = measure(ao, s, all, o);
  std::printf("%-28s %14.2f %14.2f %8.2fx\n",
              (std::to_string(ao.scene->geometry.triangleCount()) + " triangles").c_str(),
              m.one * rays * 1e-6, m.all * rays * 1e-6, m.speedUp);
  std::printf("(%s, %s, %d shading samples per camera sample; AO rays/s excludes camera rays)\n",
              aoPath.c_str(), strategyLabel(s.integrator).c_str(), s.integrator.samples);
  return 0;
}

}  // namespace

void addBenchCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "Measure rendering throughput (camera samples/s, AO rays/s)");
  cmd->add_option("--sphere-scene", o->sphereScene,
                  "Scene for the direct strategies (default: built-in hw2 sphere)");
  cmd->add_option("--ao-scene", o->aoScene,
                  "Scene for the AO benchmark (default: scenes/standin/rock-ao.xml)");
  cmd->add_option("--seconds", o->seconds, "Length of each timed run")->check(CLI::PositiveNumber);
  cmd->add_option("--repeats", o->repeats, "Timed runs per figure (the median is reported)")
      ->check(CLI::Range(1, 100));
  cmd->add_option("--threads", o->threads, "Threads for the 'all threads' column")
      ->check(CLI::Range(1, 1024));
  cmd->callback([o, &exitCode] { exitCode = runBench(*o); });
}

}  // namespace penumbra::cli
