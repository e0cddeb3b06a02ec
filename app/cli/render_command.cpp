// penumbra render: headless progressive rendering to EXR / PFM / PNG.
#include <unistd.h>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <thread>

#include "app/cli/commands.h"
#include "app/cli/scene_options.h"
#include "core/analysis/reference.h"
#include "core/image/image_io.h"
#include "core/math/error.h"
#include "core/render/engine.h"
#include "core/render/sample_count_fit.h"

namespace penumbra::cli {

namespace {

std::atomic<bool> gInterrupted{false};
extern "C" void onInterrupt(int) {
  gInterrupted = true;
}

struct RenderOptions {
  SceneOptions scene;
  std::string output;
  uint32_t spp = 0;
  double seconds = 0;
  int64_t seed = -1;
  int threads = 0;
  bool reference = false;  // converged reference: lowest-variance estimator, stored with its standard error
};

void drawProgress(const RenderProgress& p, uint32_t target, double seconds) {
  double fraction = 0;
  if (target > 0)
    fraction = double(p.spp) / target;
  else if (seconds > 0)
    fraction = p.seconds / seconds;
  fraction = std::min(fraction, 1.0);
  int filled = int(fraction * 30);
  std::fprintf(stderr, "\r[%.*s%*s] %3d%%  %u spp  %.1f s", filled,
               "==============================", 30 - filled, "", int(fraction * 100), p.spp, p.seconds);
  std::fflush(stderr);
}

int runRender(const RenderOptions& o) {
  LoadedScene loaded = o.scene.load();
  auto job = std::make_shared<RenderJob>();
  job->scene = loaded.scene;
  job->settings = loaded.settings;
  if (o.seed >= 0) job->settings.seed = uint64_t(o.seed);
  std::string output = o.output;
  if (o.reference) {
    job->settings.integrator = referenceEstimator(job->settings.integrator);
    if (o.seed < 0) job->settings.seed = kReferenceSeed;      // independent of the runs measured against it
    if (output.empty()) output = referenceCachePath(loaded);  // where `penumbra converge` looks for it
  }
  if (output.empty()) throw Error("render: -o/--output is required (optional only with --reference)");

  RenderLimits limits;
  limits.seconds = o.seconds;
  uint32_t defaultSpp = o.reference ? 4096u : job->settings.sampleCount;
  limits.targetSpp = o.spp > 0 ? o.spp : (o.seconds > 0 ? 0 : defaultSpp);
  if (std::string note = fitSampleCountToTarget(job->settings, limits.targetSpp); !note.empty())
    std::fprintf(stderr, "warning: %s\n", note.c_str());

  gInterrupted = false;
  auto previous = std::signal(SIGINT, onInterrupt);
  Engine engine;
  engine.start(job, limits, o.threads);
  bool tty = isatty(STDERR_FILENO);
  while (!engine.progress().finished) {
    if (gInterrupted) engine.requestStop();
    if (tty) drawProgress(engine.progress(), limits.targetSpp, limits.seconds);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  engine.wait();
  std::signal(SIGINT, previous);
  RenderProgress p = engine.progress();
  if (tty) {
    drawProgress(p, limits.targetSpp, limits.seconds);
    std::fprintf(stderr, "\n");
  }

  ImageMetadata meta;
  for (auto& [k, v] : describeSettings(job->settings)) meta.add(k, v);
  meta.add("spp", std::to_string(p.spp));
  meta.add("seconds", std::to_string(p.seconds));
  meta.add("scene", loaded.path.empty() ? "<built-in>" : loaded.path);
  meta.add("badSamples", std::to_string(p.badSamples));
  if (o.reference) {
    meta.add("sceneHash", sceneContentHash(loaded.desc));
    Reference ref{
        engine.film().mean(p.spp), engine.film().standardError(p.spp),
        "rendered " + strategyLabel(job->settings.integrator) + " " + std::to_string(p.spp) + " spp"};
    writeReference(output, ref, meta);  // + <output>.stderr.exr
  } else {
    writeImage(output, engine.film().mean(p.spp), meta);
  }

  const auto& cam = job->settings.camera;
  std::printf("%s: %dx%d, %u spp, %.3f s, %.2f M samples/s, %llu NaN/Inf/negative, %s, %d threads%s\n",
              output.c_str(), cam.width, cam.height, p.spp, p.seconds,
              p.seconds > 0 ? double(p.samples) / p.seconds * 1e-6 : 0.0, (unsigned long long)p.badSamples,
              strategyLabel(job->settings.integrator).c_str(), engine.threadCount(),
              gInterrupted ? " (interrupted)" : "");
  return 0;
}

}  // namespace

void addRenderCommand(CLI::App& app, int& exitCode) {
  auto opts = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene headless to .exr, .pfm or .png");
  opts->scene.addTo(*cmd);
  cmd->add_option("-o,--output", opts->output,
                  "Output image (.exr float, .pfm float, .png sRGB 8-bit); required unless --reference");
  std::string references;
  for (const StrategyRow& row : strategyTable())
    if (row.reference) (references += references.empty() ? "" : ", ") += row.label;
  cmd->add_flag(
      "--reference", opts->reference,
      "Converged reference: the lowest-variance estimator (" + references +
          "), 4096 spp unless --spp/--time, written with NAME.stderr.exr; default output: the cache "
          "next to the scene (SCENE.xml.ref-HASH.exr) that `penumbra converge` reads");
  cmd->add_option("--spp", opts->spp, "Samples per pixel (default: the scene's sampleCount)")
      ->check(CLI::Range(1u, 1u << 30));
  cmd->add_option("--time", opts->seconds, "Render for this many seconds (whole passes)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--seed", opts->seed, "Random seed (default: the scene's, else 0)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--threads", opts->threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  cmd->callback([opts, &exitCode] { exitCode = runRender(*opts); });
}

}  // namespace penumbra::cli
