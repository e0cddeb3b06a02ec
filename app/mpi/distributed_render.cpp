#include "app/mpi/distributed_render.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <limits>
#include <thread>

#include "app/cli/option_checks.h"
#include "app/cli/scene_options.h"
#include "app/mpi/interrupt_signals.h"
#include "app/mpi/rank_agreement.h"
#include "app/mpi/run_description.h"
#include "core/analysis/reference.h"
#include "core/image/atomic_file.h"
#include "core/image/image_io.h"
#include "core/math/error.h"
#include "core/render/cpu_clock.h"
#include "core/render/engine.h"
#include "core/render/memory_estimate.h"

namespace penumbra::mpi {

namespace {

using Options = DistributedRenderOptions;

struct Loaded {
  LoadedScene scene;
  std::shared_ptr<const RenderJob> job;  // its samplerNote is render's warning
  std::string output;
  uint64_t target = 0;         // samples per pixel over all ranks; 0: until the time limit
  RunDescription description;  // what this rank would render, compared between the ranks
};

const char* formatName(ImageFormat format) {
  switch (format) {
    case ImageFormat::Exr:
      return "exr";
    case ImageFormat::Pfm:
      return "pfm";
    case ImageFormat::Png:
      return "png";
  }
  return "?";
}

// Everything that can fail before rendering; runs on every rank. Only rank 0 writes, so only it
// checks the output paths.
Loaded prepare(const Options& o, int rank) {
  if ((o.block & (o.block - 1)) != 0)
    throw Error("--block must be a power of two, not " + std::to_string(o.block));
  if (!o.output.empty()) imageFormatFromPath(o.output);  // a bad extension fails before rendering
  Loaded l;
  l.scene = o.scene.load();
  RenderSettings settings = l.scene.settings;
  if (o.seed) settings.seed = *o.seed;
  l.output = o.output;
  if (o.reference) {
    settings.integrator = referenceEstimator(settings.integrator, *l.scene.scene);
    if (!o.seed) settings.seed = kReferenceSeed;
    if (l.output.empty()) l.output = referenceCachePath(l.scene);
  }
  if (l.output.empty()) throw Error("render: -o/--output is required (optional only with --reference)");
  if (rank == 0) {
    checkOutputPath(l.output);
    checkOutputPath(standardErrorPath(l.output));
  }
  const CameraDesc& cam = settings.camera;
  checkRenderFitsInMemory(cam.width, cam.height, l.scene.path.empty() ? "render" : l.scene.path);
  // The job is made for the whole run's count, as in render (not for one rank's passes): every rank
  // the same, so stratified and zsobol draw one pattern and the ranks' blocks of sample indices are
  // blocks of it.
  l.target = o.spp > 0 ? o.spp : (o.seconds > 0 ? 0 : (o.reference ? 4096u : settings.sampleCount));
  l.job =
      std::make_shared<const RenderJob>(l.scene.scene, settings, RenderLimits{uint32_t(l.target), o.seconds});
  const RunChoices choices{l.target, o.seconds, o.block, o.reference,
                           formatName(imageFormatFromPath(l.output))};
  l.description = describeRun(l.job->settings, choices, l.scene.desc);
  return l;
}

// Mean and standard error of the reduced film, row y of rowSpp[y] samples, the rows split over
// `threads` threads: after an interrupt the grace before mpirun's SIGKILL is short, and a serial
// resolve of 1080p takes ~0.2 s.
Reference resolveInParallel(const Film& film, const std::vector<uint32_t>& rowSpp, int threads,
                            std::string how) {
  Reference ref;
  ref.mean = Image(film.width(), film.height());
  ref.standardError = Image(film.width(), film.height());
  const int height = film.height(), n = std::clamp(threads, 1, std::max(1, height));
  std::vector<std::thread> pool;
  for (int t = 0; t < n; ++t)
    pool.emplace_back([&, t] {
      const int y0 = height * t / n, y1 = height * (t + 1) / n;
      film.resolveMean(rowSpp, ref.mean, y0, y1);
      film.resolveStandardError(rowSpp, ref.standardError, y0, y1);
    });
  for (std::thread& worker : pool) worker.join();
  ref.source = std::move(how);
  return ref;
}

std::string joined(const std::vector<uint64_t>& values) {
  std::string out;
  for (uint64_t v : values) out += (out.empty() ? "" : ",") + std::to_string(v);
  return out;
}

// Runs of rows with the same count, top row first: "S*R,..." is R rows of S samples each.
std::string rowRuns(const std::vector<uint32_t>& rowSpp) {
  std::string out;
  for (size_t y = 0; y < rowSpp.size();) {
    size_t end = y;
    while (end < rowSpp.size() && rowSpp[end] == rowSpp[y]) ++end;
    out += (out.empty() ? "" : ",") + std::to_string(rowSpp[y]) + "*" + std::to_string(end - y);
    y = end;
  }
  return out;
}

// The rows whose flag is set, as inclusive ranges "a-b" (or "a"), comma-separated; "" for none.
std::string rowRanges(const uint64_t* flags, size_t rows) {
  std::string out;
  for (size_t y = 0; y < rows;) {
    if (!flags[y]) {
      ++y;
      continue;
    }
    size_t last = y;
    while (last + 1 < rows && flags[last + 1]) ++last;
    out += (out.empty() ? "" : ",") + std::to_string(y) + (last > y ? "-" + std::to_string(last) : "");
    y = last + 1;
  }
  return out;
}

void drawProgress(uint64_t spp, uint64_t target, double seconds, double limit) {
  double fraction = target > 0 ? double(spp) / double(target) : (limit > 0 ? seconds / limit : 0.0);
  fraction = std::min(fraction, 1.0);
  const int filled = int(fraction * 30);
  std::fprintf(stderr, "\r[%.*s%*s] %3d%%  ~%llu spp  %.1f s", filled,
               "==============================", 30 - filled, "", int(fraction * 100),
               (unsigned long long)spp, seconds);
  std::fflush(stderr);
}

}  // namespace

int runDistributedRender(const Options& o, const Session& mpi) {
  const int rank = mpi.rank(), ranks = mpi.size();
  // Every rank loads and checks, then the ranks compare what they would render: on a failure or a
  // disagreement rank 0 says what and where, and no rank renders.
  Loaded l;
  std::string failure;
  try {
    l = prepare(o, rank);
  } catch (const std::exception& e) {
    failure = e.what();
  }
  if (!everyRankSucceeded(mpi, failure)) return kExitBadInput;
  if (!everyRankAgrees(mpi, l.description)) return kExitBadInput;

  if (rank == 0 && !l.job->samplerNote.empty())
    std::fprintf(stderr, "warning: %s\n", l.job->samplerNote.c_str());
  // Temporaries of this output left by a process killed while writing (a SIGKILL mid-write).
  if (rank == 0) {
    removeStaleTemporaries(l.output);
    removeStaleTemporaries(standardErrorPath(l.output));
  }
  const RenderSettings& s = l.job->settings;
  const uint32_t block = o.block;
  const uint64_t target = l.target;
  const SampleSchedule schedule = SampleSchedule::blocks(block, uint32_t(rank), uint32_t(ranks));
  RenderLimits limits;
  const uint64_t myPasses = target > 0 ? schedule.passesBelow(target) : std::numeric_limits<uint32_t>::max();
  // Rounds until every index below the target is rendered: rank r renders its m-th block in round m.
  const uint64_t rounds =
      target > 0 ? ((target + block - 1) / block + ranks - 1) / ranks : std::numeric_limits<uint64_t>::max();
  const int threads = o.threads > 0
                          ? o.threads
                          : std::max(1, int(std::thread::hardware_concurrency()) / mpi.ranksOnThisNode());

  // Rank 0's receive buffer for the film sums, allocated (and its pages touched) now rather than when
  // an interrupt leaves little time.
  const CameraDesc& cam = s.camera;
  const size_t sumCount = size_t(cam.width) * cam.height * 6;
  std::vector<double> total(rank == 0 ? sumCount : 0, 0.0);

  const InterruptSignals signals;

  const bool tty = rank == 0 && isatty(STDERR_FILENO);
  double lastLogLine = -1e9;  // without a terminal: a progress line at most every 10 s
  Engine engine;
  bool started = false;
  mpi.barrier();  // start together: the time limit counts from here
  const double t0 = mpi.wallSeconds();
  const double cpu0 = processCpuSeconds();
  bool interrupted = false;
  for (uint64_t round = 0;; ++round) {
    // Rank 0 decides on time at block boundaries; any rank's interrupt stops everyone.
    int stop = signals.interrupted() ? 2 : 0;  // 2: interrupted, 1: time is up
    if (rank == 0 && o.seconds > 0 && mpi.wallSeconds() - t0 >= o.seconds) stop = std::max(stop, 1);
    stop = mpi.maxOf(stop);
    if (stop == 2) interrupted = true;
    if (stop || round >= rounds) break;
    if (rank == 0 && !tty && round > 0 && mpi.wallSeconds() - lastLogLine >= 10) {
      lastLogLine = mpi.wallSeconds();
      std::fprintf(stderr, "progress: ~%llu spp, %.1f s\n",
                   (unsigned long long)(uint64_t(engine.progress().spp) * ranks), lastLogLine - t0);
      std::fflush(stderr);
    }
    const uint32_t roundTarget = uint32_t(std::min<uint64_t>((round + 1) * block, myPasses));
    const uint32_t done = started ? engine.progress().spp : 0;
    if (roundTarget <= done) continue;  // no block of this rank in this round (the last one)
    limits.targetSpp = roundTarget;
    if (!started) {
      engine.start(l.job, limits, threads, schedule);
      started = true;
    } else if (!engine.extend(limits)) {
      throw Error("the engine could not continue the accumulation");
    }
    for (unsigned poll = 0; !engine.progress().finished; ++poll) {
      // Ends within a pixel, keeping the rows that completed the running pass (Engine::stopNow).
      if (signals.interrupted()) engine.stopNow();
      if (tty && poll % 4 == 0)
        drawProgress(uint64_t(engine.progress().spp) * ranks, target, mpi.wallSeconds() - t0, o.seconds);
      std::this_thread::sleep_for(std::chrono::milliseconds(5));  // an interrupt is seen within 5 ms
    }
    engine.wait();
  }
  const double renderSeconds = mpi.wallSeconds() - t0;
  if (interrupted && rank == 0) {
    const int sig = signals.signal();
    std::fprintf(stderr, "%sinterrupted (%s%s): writing the rows every rank has completed\n", tty ? "\n" : "",
                 sig ? strsignal(sig) : "on another rank",
                 sig == SIGCONT ? ", mpirun is ending the job" : "");
    std::fflush(stderr);
  }

  // The reduction: the film sums (sent from the engine's film, received into rank 0's `total`,
  // allocated before the render), and the counts (passes, bad samples, CPU microseconds), every
  // rank's passes n (its schedule's passes [0, n) in every row) and the rows where it also has pass n
  // (an interrupt stops inside a pass, keeping the rows that completed it).
  const RenderProgress mine = started ? engine.progress() : RenderProgress{};
  std::vector<uint64_t> counts = {mine.spp, mine.badSamples, uint64_t((processCpuSeconds() - cpu0) * 1e6)};
  std::vector<uint64_t> rankPasses(size_t(ranks), 0);
  rankPasses[size_t(rank)] = mine.spp;
  const size_t height = size_t(cam.height);
  std::vector<uint64_t> rowsAhead(size_t(ranks) * height, 0);  // [r * height + y]: rank r, row y
  if (started)
    for (size_t y = 0; y < height; ++y)
      rowsAhead[size_t(rank) * height + y] = engine.rowPasses()[y] > mine.spp;
  const std::vector<double> noSums = started ? std::vector<double>{} : std::vector<double>(sumCount, 0.0);
  mpi.barrier();  // the last round's stragglers: waited for asleep, and not counted as reduction time
  const double r0 = mpi.wallSeconds();
  mpi.sumToRoot(started ? engine.film().sums() : noSums, total);
  mpi.sumToRoot(counts);
  mpi.sumToRoot(rankPasses);
  mpi.sumToRoot(rowsAhead);
  const double reduceSeconds = mpi.wallSeconds() - r0;
  const int maxThreads = mpi.maxOf(started ? engine.threadCount() : threads);
  if (rank != 0) {
    // Asleep until rank 0 has written (its cores are the write's), with the interrupt handlers still
    // installed: a rank ended by mpirun's SIGTERM would make mpirun end the job, rank 0 with it.
    mpi.barrier();
    return interrupted ? kExitInterrupted : 0;
  }

  if (tty) {
    drawProgress(counts[0], target, renderSeconds, o.seconds);
    std::fprintf(stderr, "\n");
  }
  // Samples per pixel of each row: every rank's passes, and one more where it is ahead.
  std::vector<uint32_t> rowSpp(height, 0);
  for (size_t y = 0; y < height; ++y)
    for (int r = 0; r < ranks; ++r)
      rowSpp[y] += uint32_t(rankPasses[size_t(r)] + rowsAhead[size_t(r) * height + y]);
  const uint32_t spp = *std::min_element(rowSpp.begin(), rowSpp.end());
  const uint32_t maxSpp = *std::max_element(rowSpp.begin(), rowSpp.end());
  uint64_t samples = 0;
  for (uint32_t n : rowSpp) samples += uint64_t(n) * uint64_t(cam.width);
  const double seconds = mpi.wallSeconds() - t0;
  const Film film(cam.width, cam.height, std::move(total));  // no copy, no zeroing of 100 MB at 1080p
  ImageMetadata meta;
  for (auto& [k, v] : describeSettings(s)) meta.add(k, v);
  meta.add("spp", std::to_string(spp));
  meta.add("seconds", std::to_string(seconds));
  meta.add("scene", l.scene.path.empty() ? "<built-in>" : l.scene.path);
  meta.add("badSamples", std::to_string(counts[1]));
  meta.add("mpiRanks", std::to_string(ranks));
  meta.add("threadsPerRank", std::to_string(maxThreads));
  meta.add("sampleBlock", std::to_string(block));
  meta.add("rankPasses", joined(rankPasses));
  if (maxSpp > spp) {  // stopped inside a pass: which rows have which samples
    meta.add("rowSpp", rowRuns(rowSpp));
    std::string ahead;
    for (int r = 0; r < ranks; ++r)
      ahead += (r ? ";" : "") + rowRanges(rowsAhead.data() + size_t(r) * height, height);
    meta.add("rankRowsAhead", ahead);
  }
  meta.add("cpuSeconds", std::to_string(double(counts[2]) * 1e-6));
  meta.add("reduceSeconds", std::to_string(reduceSeconds));
  if (interrupted) meta.add("interrupted", "true");
  const std::string sppText = std::to_string(spp) + (maxSpp > spp ? "-" + std::to_string(maxSpp) : "");
  const std::string how = "rendered " + strategyLabel(s.integrator) + " " + sppText + " spp on " +
                          std::to_string(ranks) + " MPI ranks x " + std::to_string(maxThreads) + " threads";
  if (o.reference) meta.add("sceneHash", sceneContentHash(l.scene.desc));
  if (spp == 0) throw Error("no pass was completed in every row; nothing written");
  // writeReference: the mean (with "reference" = how it was made), then OUT.stderr.exr; both atomic.
  // After an interrupt, uncompressed: several times faster than ZIP, and mpirun's SIGKILL is near.
  const double w0 = mpi.wallSeconds();
  const int resolveThreads = std::max({1, threads, int(std::thread::hardware_concurrency())});
  writeReference(l.output, resolveInParallel(film, rowSpp, resolveThreads, how), meta,
                 interrupted ? ExrCompression::None : ExrCompression::Zip);
  const double writeSeconds = mpi.wallSeconds() - w0;
  const double writtenAfterSignal = signals.interrupted() ? signals.secondsSinceInterrupt() : 0.0;
  mpi.barrier();  // the other ranks wait here for the write

  std::printf(
      "%s: %dx%d, %s spp, %.3f s (reduction %.3f s, write %.3f s), %.2f M samples/s, %llu NaN/Inf/negative, "
      "%s, %d ranks x %d threads, %.2f CPU s",
      l.output.c_str(), cam.width, cam.height, sppText.c_str(), seconds, reduceSeconds, writeSeconds,
      seconds > 0 ? double(samples) / seconds * 1e-6 : 0.0, (unsigned long long)counts[1],
      strategyLabel(s.integrator).c_str(), ranks, maxThreads, double(counts[2]) * 1e-6);
  if (interrupted && signals.interrupted())
    std::printf(" (interrupted; written %.3f s after the signal)", writtenAfterSignal);
  else if (interrupted)
    std::printf(" (interrupted on another rank)");
  std::printf("\n");
  std::fflush(stdout);
  return interrupted ? kExitInterrupted : 0;
}

CLI::App* addDistributedRenderCommand(CLI::App& app, Options& options) {
  Options* opts = &options;
  CLI::App* cmd = app.add_subcommand(
      "render", "Render a scene over the ranks of an MPI job; rank 0 writes OUT and OUT.stderr.exr");
  opts->scene.addTo(*cmd);
  cmd->add_option("-o,--output", opts->output,
                  "Output image (.exr, .pfm or .png); required unless --reference");
  cmd->add_flag(
      "--reference", opts->reference,
      "Converged reference (as `penumbra render --reference`): the lowest-variance estimator, 4096 spp "
      "unless --spp/--time, default output the cache next to the scene that `penumbra converge` reads");
  cmd->add_option("--spp", opts->spp, "Samples per pixel over all ranks (default: the scene's sampleCount)")
      ->check(CLI::Range(1u, 1u << 30));
  cmd->add_option("--time", opts->seconds, "Render for this many seconds (whole blocks on every rank)")
      ->check(cli::finitePositiveNumber());
  cli::addSeedOption(*cmd, opts->seed, "Random seed (default: the scene's, else 0)");
  cmd->add_option("--threads", opts->threads,
                  "Worker threads per rank (default: the cores over the ranks on a node)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option(
         "--block", opts->block,
         "Sample indices per block, a power of two: rank r renders blocks r, r+K, r+2K, ... (default 16)")
      ->check(CLI::Range(1u, 1u << 20));
  return cmd;
}

}  // namespace penumbra::mpi
