// penumbra render: headless progressive rendering to EXR / PFM / PNG.
#include <unistd.h>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>

#include "app/cli/commands.h"
#include "app/cli/display_server_option.h"
#include "app/cli/option_checks.h"
#include "app/cli/scene_options.h"
#include "core/analysis/reference.h"
#include "core/image/atomic_file.h"
#include "core/image/image_io.h"
#include "core/math/error.h"
#include "core/render/engine.h"
#include "core/render/memory_estimate.h"
#include "core/render/publish_signal.h"
#include "core/render/row_renderer.h"
#include "core/scene/light_selection_default.h"

namespace penumbra::cli {

namespace {

// Ctrl-C: the first abandons the running pass (the engine checks per pixel) and writes the passes
// completed so far; a second one, while that is being written, exits at once without writing.
// Handler state is only lock-free atomics and preformatted text (async-signal-safe).
std::atomic<int> gInterrupts{0};
std::atomic<bool> gWritten{false};
char gNotWrittenMessage[1024] = "\ninterrupted again: stopped at once, nothing written\n";
char gWrittenMessage[1024] = "\ninterrupted again: stopped at once, the image was already written\n";

extern "C" void onInterrupt(int) {
  if (gInterrupts.fetch_add(1) == 0) return;
  const char* m = gWritten.load() ? gWrittenMessage : gNotWrittenMessage;
  ssize_t ignored = ::write(STDERR_FILENO, m, std::strlen(m));
  (void)ignored;
  ::_exit(kExitInterrupted);
}

struct RenderOptions {
  SceneOptions scene;
  std::string output;
  uint32_t spp = 0;
  double seconds = 0;
  std::optional<uint64_t> seed;  // default: the scene's
  int threads = 0;
  bool reference = false;  // converged reference: lowest-variance estimator, stored with its standard error
  DisplayServerOption display;
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
  std::optional<net::DisplayServer> displayServer = o.display.resolve();
  LoadedScene loaded = o.scene.load();
  RenderSettings settings = loaded.settings;
  if (o.seed) settings.seed = *o.seed;
  std::string output = o.output;
  if (o.reference) {
    settings.integrator = referenceEstimator(settings.integrator, *loaded.scene);
    if (!o.seed) settings.seed = kReferenceSeed;              // independent of the runs measured against it
    if (output.empty()) output = referenceCachePath(loaded);  // where `penumbra converge` looks for it
  }
  if (output.empty()) throw Error("render: -o/--output is required (optional only with --reference)");
  // Everything that can fail after rendering is checked before the first sample.
  imageFormatFromPath(output);
  checkOutputPath(output);
  if (o.reference) checkOutputPath(standardErrorPath(output));
  checkRenderFitsInMemory(settings.camera.width, settings.camera.height,
                          loaded.path.empty() ? "render" : loaded.path);

  RenderLimits limits;
  limits.seconds = o.seconds;
  uint32_t defaultSpp = o.reference ? 4096u : settings.sampleCount;
  limits.targetSpp = o.spp > 0 ? o.spp : (o.seconds > 0 ? 0 : defaultSpp);
  const auto job = std::make_shared<const RenderJob>(loaded.scene, settings, limits);
  if (!job->samplerNote.empty()) std::fprintf(stderr, "warning: %s\n", job->samplerNote.c_str());

  std::snprintf(gNotWrittenMessage, sizeof gNotWrittenMessage,
                "\ninterrupted again: stopped at once; %s not written (an existing file is unchanged)\n",
                output.c_str());
  std::snprintf(gWrittenMessage, sizeof gWrittenMessage,
                "\ninterrupted again: stopped at once; %s had been written\n", output.c_str());
  gInterrupts = 0;
  gWritten = false;
  auto previous = std::signal(SIGINT, onInterrupt);
  Engine engine;
  // Wakes the loop below when a pass is published or the render ends, so a short render is written
  // as soon as it finishes rather than at the next poll.
  auto published = std::make_shared<PublishSignal>();
  engine.setPublishSignal(published);
  engine.start(job, limits, o.threads);
  net::TevStreamOptions streamOptions;
  streamOptions.renderThreads = engine.threadCount();
  std::unique_ptr<net::TevStreamer> tev = openStream(displayServer, streamOptions);
  const std::string tevName = tevImageName(loaded.path, job->settings.integrator);
  bool tty = isatty(STDERR_FILENO);
  bool interrupted = false;
  // This loop is the engine's only snapshot reader, with or without a stream, so streaming cannot
  // change what an interrupted render writes: `latest`, the newest pass boundary published.
  FilmSnapshot latest;
  bool streamAsked = false;  // a snapshot the stream wanted is on its way
  auto lastRequest = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  uint64_t publications = 0;
  while (!engine.progress().finished) {
    // A pass boundary at most about half a second old stays published, so an interrupted render can
    // write whole passes; a one-pass request resolves that pass row by row and holds up no worker.
    // The stream asks for more, never for less.
    const auto now = std::chrono::steady_clock::now();
    const net::TevStreamer::Want want = tev ? tev->wanted() : net::TevStreamer::Want{};
    if (now - lastRequest >= std::chrono::milliseconds(500) || (want.frame && !streamAsked)) {
      engine.requestNextPassSnapshot(o.reference || want.withError);
      lastRequest = now;
      streamAsked = streamAsked || want.frame;
    }
    if (engine.takeSnapshot(latest)) {
      streamAsked = false;
      if (tev) tev->offer(tevName, latest, true);  // copied only when the stream takes it
    }
    if (gInterrupts > 0) {
      engine.cancel();
      interrupted = true;
      break;
    }
    if (tty) drawProgress(engine.progress(), limits.targetSpp, limits.seconds);
    publications = published->wait(publications, 0.05);  // Ctrl-C and the progress bar: every 50 ms
  }
  engine.wait();
  RenderProgress p = engine.progress();
  engine.takeSnapshot(latest);
  if (tty) {
    drawProgress(p, limits.targetSpp, limits.seconds);
    std::fprintf(stderr, "\n");
  }
  // What is written: `final`, the last completed pass boundary. An interrupted render's film also
  // holds part of the abandoned pass, so it writes the newest published snapshot; a finished render's
  // last pass was resolved by the workers as they rendered it when its target was a pass count, and
  // is resolved here otherwise.
  FilmSnapshot& final = latest;
  if (interrupted) {
    p.spp = final.spp;
    p.seconds = final.seconds;
    p.samples =
        uint64_t(final.spp) * uint64_t(job->settings.camera.width) * uint64_t(job->settings.camera.height);
    const bool complete = final.spp > 0 && (!o.reference || final.standardError.width > 0);
    if (!complete) {
      std::printf("%s: interrupted before %s: nothing written%s\n", output.c_str(),
                  final.spp == 0 ? "the first pass completed" : "a pass with its standard error completed",
                  std::filesystem::exists(output) ? " (the existing file is unchanged)" : "");
      if (tev) tev->finish();
      std::signal(SIGINT, previous);
      return kExitInterrupted;
    }
  } else {
    const bool current = final.spp == p.spp;
    if (!current || final.mean.width == 0) final.mean = engine.film().mean(p.spp);
    if ((o.reference || tev) && (!current || final.standardError.width == 0))
      final.standardError = engine.film().standardError(p.spp);
    final.spp = p.spp;
  }

  ImageMetadata meta;
  for (auto& [k, v] : describeSettings(job->settings)) meta.add(k, v);
  meta.add("spp", std::to_string(p.spp));
  meta.add("seconds", std::to_string(p.seconds));
  meta.add("scene", loaded.path.empty() ? "<built-in>" : loaded.path);
  meta.add("badSamples", std::to_string(p.badSamples));
  meta.add("interrupted", interrupted ? "true" : "false");
  // Whether the light selection was the scene's or the light-count default (a reference has its own).
  const std::string selection =
      job->settings.integrator == loaded.settings.integrator
          ? lightSelectionSummary(loaded.desc, job->settings.integrator, loaded.scene->areaLightCount())
          : "";
  if (!selection.empty()) meta.add("lightSelectionChoice", selection);
  if (o.reference) {
    meta.add("sceneHash", sceneContentHash(loaded.desc));
    // A reference render is long: copying its two images for the Reference costs nothing in comparison.
    const std::string source =
        "rendered " + strategyLabel(job->settings.integrator) + " " + std::to_string(p.spp) + " spp";
    writeReference(output, Reference{final.mean, final.standardError, source},
                   meta);  // + <output>.stderr.exr
  } else {
    writeImage(output, final.mean, meta);
  }
  gWritten = true;

  const auto& cam = job->settings.camera;
  std::printf("%s: %dx%d, %u spp, %.3f s, %.2f M samples/s, %llu NaN/Inf/negative, %s, %d threads%s\n",
              output.c_str(), cam.width, cam.height, p.spp, p.seconds,
              p.seconds > 0 ? double(p.samples) / p.seconds * 1e-6 : 0.0, (unsigned long long)p.badSamples,
              strategyLabel(job->settings.integrator).c_str(), engine.threadCount(),
              interrupted ? " (interrupted: the completed passes were written)" : "");
  if (!selection.empty()) std::printf("%s\n", selection.c_str());
  std::printf("row loop: %s\n", rowLoopSummary(*job).c_str());
  std::fflush(stdout);
  // At most TevStreamOptions::waitSeconds more.
  if (tev) tev->finish(net::TevFrame{tevName, final.mean, final.standardError, true});
  std::signal(SIGINT, previous);
  return interrupted ? kExitInterrupted : 0;
}

}  // namespace

void addRenderCommand(CLI::App& app, int& exitCode) {
  auto opts = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene headless to .exr, .pfm or .png");
  opts->scene.addTo(*cmd);
  cmd->add_option("-o,--output", opts->output,
                  "Output image (.exr float, .pfm float, .png sRGB 8-bit); required unless --reference");
  std::string references;
  for (const IntegratorType type : {IntegratorType::Direct, IntegratorType::Ao})
    (references += references.empty() ? "" : ", ") +=
        strategyLabel(referenceStrategy(integratorOfType(type)));
  references += "; with glossy surfaces " +
                strategyLabel(referenceStrategy(integratorOfType(IntegratorType::Direct), true));
  cmd->add_flag(
      "--reference", opts->reference,
      "Converged reference: the lowest-variance estimator (" + references +
          "), 4096 spp unless --spp/--time, written with NAME.stderr.exr; default output: the cache "
          "next to the scene (SCENE.xml.ref-HASH.exr) that `penumbra converge` reads");
  cmd->add_option("--spp", opts->spp, "Samples per pixel (default: the scene's sampleCount)")
      ->check(CLI::Range(1u, 1u << 30));
  cmd->add_option("--time", opts->seconds, "Render for this many seconds (whole passes)")
      ->check(finitePositiveNumber());
  addSeedOption(*cmd, opts->seed, "Random seed (default: the scene's, else 0)");
  cmd->add_option("--threads", opts->threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  opts->display.addTo(*cmd);
  cmd->callback([opts, &exitCode] { exitCode = runRender(*opts); });
}

}  // namespace penumbra::cli
