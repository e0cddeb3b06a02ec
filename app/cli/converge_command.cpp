// penumbra converge: error against run time (or spp) for every sampling strategy, crossed with the
// samplers named by --samplers.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "app/cli/commands.h"
#include "app/cli/convergence_report.h"
#include "app/cli/display_server_option.h"
#include "app/cli/option_checks.h"
#include "app/cli/scene_options.h"
#include "core/analysis/convergence.h"
#include "core/image/atomic_file.h"
#include "core/math/error.h"
#include "core/render/strategy_axes.h"
#include "core/sampling/sampler_table.h"

namespace penumbra::cli {

namespace {

struct ConvergeOptions {
  SceneOptions scene;
  StrategyLists lists{"all", "", "", ""};
  std::string samplers;  // empty: the scene's sampler
  double seconds = 0;
  uint32_t spp = 0;
  std::string reference;
  std::string cacheDir;
  uint32_t referenceSpp = 4096;
  std::string outDir;
  int threads = 0;
  uint64_t seed = 0;
  std::string timeAxis = "wall";
  DisplayServerOption display;
};

void logLine(const std::string& s) {
  std::fprintf(stderr, "%s\n", s.c_str());
}

// The directories of `dir` that do not exist yet (deepest first), which prepareOutputDirectory will
// make; removed again, while still empty, unless kept: a converge that fails before its report leaves
// no empty output directory behind.
class NewDirectories {
 public:
  explicit NewDirectories(const std::string& dir) {
    std::error_code ec;
    std::filesystem::path p = std::filesystem::path(dir).lexically_normal();
    if (p.filename().empty()) p = p.parent_path();  // "out/"
    for (; !p.empty() && !std::filesystem::exists(p, ec); p = p.parent_path()) missing_.push_back(p);
  }
  ~NewDirectories() {
    std::error_code ec;
    if (!kept_)
      for (const std::filesystem::path& p : missing_) std::filesystem::remove(p, ec);  // only if empty
  }
  NewDirectories(const NewDirectories&) = delete;
  NewDirectories& operator=(const NewDirectories&) = delete;
  void keep() { kept_ = true; }

 private:
  std::vector<std::filesystem::path> missing_;
  bool kept_ = false;
};

// Creates `dir` if missing and checks that each of `files` can be written in it (checkOutputPath).
void prepareOutputDirectory(const std::string& dir, const std::vector<std::string>& files) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
    throw Error("-o " + dir + ": exists and is not a directory");
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error("-o " + dir + ": cannot create the output directory: " + ec.message());
  for (const std::string& f : files) checkOutputPath(dir + "/" + f);
}

int runConverge(const ConvergeOptions& o) {
  std::optional<net::DisplayServer> displayServer = o.display.resolve();
  LoadedScene loaded = o.scene.load();
  if (o.spp == 0 && o.seconds <= 0) throw Error("converge: give --time SECONDS or --spp N");
  ParsedStrategies parsed = parseStrategyLists(loaded.settings.integrator, o.lists);
  for (const std::string& notice : parsed.notices) std::fprintf(stderr, "%s\n", notice.c_str());
  const std::vector<IntegratorDesc>& strategies = parsed.strategies;
  std::vector<SamplerKind> samplers = parseSamplers(loaded.settings.samplerKind, o.samplers);
  if (o.seed == kReferenceSeed) throw Error("converge: --seed must differ from the reference's seed");
  // The report's files can be written (the directory is made if missing): found now, not after the runs.
  const std::vector<std::string> reportFiles = {"convergence.csv", "convergence.png", "equal-time.png",
                                                "summary.md"};
  NewDirectories made(o.outDir);
  prepareOutputDirectory(o.outDir, reportFiles);
  std::unique_ptr<net::TevStreamer> tev = openStream(displayServer);  // each strategy's final image
  ReferenceRequest rq;
  rq.path = o.reference;
  rq.cacheDir = o.cacheDir;
  rq.referenceSpp = o.referenceSpp;
  rq.threads = o.threads;
  Reference ref = obtainReference(loaded, rq, logLine);
  std::vector<uint8_t> mask = emitterMask(loaded);

  ConvergenceOptions co;
  co.seconds = o.seconds;
  co.spp = o.spp;
  co.threads = o.threads;
  co.seed = o.seed;
  std::vector<ConvergenceRun> runs;
  for (const IntegratorDesc& s : strategies)
    for (SamplerKind sampler : samplers) {
      runs.push_back(runConvergence(loaded, s, sampler, ref, mask, co));
      const ConvergenceRun& r = runs.back();
      std::printf("%-28s %-12s %6u spp  %7.2f s  RMSE %.4e  (no-light %.4e)  %zu points\n",
                  r.strategy.c_str(), samplerKindName(r.sampler), r.spp, r.seconds,
                  r.points.back().error.all.rmse, r.points.back().error.noLight.rmse, r.points.size());
      const std::string suffix =
          samplers.size() > 1 ? std::string(" ") + samplerKindName(sampler) + " converge" : " converge";
      if (tev) tev->send(net::TevFrame{tevImageName(loaded.path, s, suffix), r.finalImage, Image()});
    }

  ReportInfo info;
  info.sceneName =
      loaded.path.empty() ? "built-in scene" : std::filesystem::path(loaded.path).filename().string();
  info.referenceSource = ref.source;
  info.sppMode = o.spp > 0;
  info.cpuAxis = o.timeAxis == "cpu";
  info.budget = o.spp > 0 ? double(o.spp) : o.seconds;
  info.threads = o.threads;
  info.width = ref.mean.width;
  info.height = ref.mean.height;
  info.pixels = ref.mean.pixelCount();
  info.noLightPixels = runs.empty() ? 0 : runs.front().points.back().error.noLight.pixels;
  made.keep();
  std::string dir = o.outDir + "/";
  writeConvergenceCsv(dir + "convergence.csv", runs);
  plotConvergence(dir + "convergence.png", runs, info);
  writeEqualTimeImage(dir + "equal-time.png", runs, ref, info);
  writeSummary(dir + "summary.md", runs, info);
  std::printf("wrote %sconvergence.csv, convergence.png, equal-time.png, summary.md\n", dir.c_str());
  return 0;
}

}  // namespace

void addConvergeCommand(CLI::App& app, int& exitCode) {
  auto opts = std::make_shared<ConvergeOptions>();
  CLI::App* cmd = app.add_subcommand("converge", "Error against time (or spp) for every sampling strategy");
  opts->scene.addTo(*cmd);
  cmd->add_option("--strategies", opts->lists.strategies,
                  "all, or a comma-separated list of measures (" + strategyNamesHelp() + ")");
  cmd->add_option("--light-selection", opts->lists.lightSelections,
                  "Light selections to cross with each light measure (" + acceptedLightSelections(false) +
                      "; default: the scene's)");
  cmd->add_option("--light-measure", opts->lists.lightMeasures,
                  "Light measures to cross with mis (" + acceptedLightMeasures(false) +
                      "; default: the scene's, else solid-angle)");
  cmd->add_option("--heuristic", opts->lists.heuristics,
                  "MIS heuristics to cross with mis (" + acceptedHeuristics(false) +
                      "; default: the scene's, else power)");
  cmd->add_option("--samplers", opts->samplers,
                  "Comma-separated samplers to cross with the strategies, or all (" + acceptedSamplerNames() +
                      "; default: the scene's sampler)");
  cmd->add_option("--time", opts->seconds, "Seconds per strategy and sampler (error against time)")
      ->check(finitePositiveNumber());
  cmd->add_option("--spp", opts->spp, "Samples per pixel per strategy and sampler (error against samples)")
      ->check(CLI::Range(1u, 1u << 24));
  cmd->add_option(
      "--reference", opts->reference,
      "Reference EXR/PFM (a sibling NAME.stderr.exr adds its standard error), or closed-form; "
      "default: closed form for scenes/analytic, else the cached or a freshly rendered reference");
  cmd->add_option("--reference-spp", opts->referenceSpp, "spp of a reference rendered because none is cached")
      ->check(CLI::Range(1u, 1u << 24));
  cmd->add_option("--cache-dir", opts->cacheDir, "Where cached references live (default: next to the scene)");
  cmd->add_option("-o,--output", opts->outDir, "Output directory")->required();
  cmd->add_option("--threads", opts->threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  addSeedOption(*cmd, opts->seed, "Random seed");
  cmd->add_option("--time-axis", opts->timeAxis,
                  "x axis of convergence.png in time mode: wall (default) or cpu (the render's CPU seconds, "
                  "stable when other processes compete for the cores)")
      ->check(CLI::IsMember({"wall", "cpu"}));
  opts->display.addTo(*cmd);
  cmd->callback([opts, &exitCode] { exitCode = runConverge(*opts); });
}

}  // namespace penumbra::cli
