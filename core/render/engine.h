// Progressive renderer: whole-image passes of one sample per pixel on a pool of worker threads.
// Pass p uses sample index p in every pixel, so the image depends only on (scene, settings, seed),
// never on thread count or scheduling. Cancellation takes effect within one pixel (its samples).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "core/image/image.h"
#include "core/render/film.h"
#include "core/render/render_settings.h"
#include "core/world/scene.h"

namespace penumbra {

struct RenderJob {
  std::shared_ptr<const Scene> scene;
  RenderSettings settings;
};

struct RenderLimits {
  uint32_t targetSpp = 0;  // 0: no limit
  double seconds = 0.0;    // 0: no limit; checked at pass boundaries
  // Before the first pass, render one sample per kPreviewBlock^2 block and publish it (upscaled) as
  // a snapshot with spp 0, so an interactive view shows the new estimate within milliseconds.
  bool preview = false;
};

inline constexpr int kPreviewBlock = 4;

struct RenderProgress {
  uint32_t spp = 0;          // completed passes
  double seconds = 0.0;      // rendering time, pauses excluded
  double passSeconds = 0.0;  // rendering time when pass `spp` completed (rates independent of polling)
  uint64_t samples = 0;      // camera samples accumulated
  uint64_t badSamples = 0;   // NaN, Inf or negative values (dropped and counted)
  bool finished = false;
};

// CPU time of all this process's threads, in seconds (what FilmSnapshot::cpuSeconds counts).
double processCpuSeconds();

// The current mean (and standard error) as published at a pass boundary.
struct FilmSnapshot {
  uint64_t version = 0;
  uint32_t spp = 0;
  double seconds = 0.0;
  // Process CPU time (all threads) since start(), read at this pass boundary. Unlike `seconds` it does
  // not grow while other processes hold the cores, so error-against-CPU-time is stable on a shared
  // machine (analysis/convergence.h). Includes whatever else the process runs (e.g. a UI thread).
  double cpuSeconds = 0.0;
  Image mean;
  Image standardError;  // only when requested (a whole-image resolve)
  // One pixel's statistics at this boundary (Engine::setProbePixel): a pixel inspector's standard
  // error without resolving the whole image's. x < 0: none.
  struct Probe {
    int x = -1, y = -1;
    Color3 mean{0.f}, standardError{0.f};
  } probe;
};

// Counts snapshot publications, so a viewer can sleep until one of its engines has something new
// (Engine::setPublishSignal) instead of polling.
class PublishSignal {
 public:
  void notify();
  uint64_t count() const;
  // Waits until count() differs from `seen`, or `seconds` pass; returns count().
  uint64_t wait(uint64_t seen, double seconds) const;

 private:
  mutable std::mutex mutex_;
  mutable std::condition_variable cv_;
  uint64_t count_ = 0;
};

class Engine {
 public:
  Engine() = default;
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  // Starts a fresh accumulation (cancelling any running one). threads <= 0: all cores.
  void start(std::shared_ptr<const RenderJob> job, RenderLimits limits = {}, int threads = 0);
  // Abandons the running pass and joins the workers; the film keeps the completed passes.
  void cancel();
  // Finishes the current pass, then stops (what Ctrl-C in `penumbra render` does).
  void requestStop();
  // New limits for the current accumulation, without restarting it: a running render adopts them at
  // its next pass boundary; a render that stopped at its old limits resumes where it left off.
  // Returns false (and changes nothing) when there is no accumulation to extend.
  bool extend(RenderLimits limits);
  // Blocks until the limits are reached or the render is stopped.
  void wait();
  void setPaused(bool paused);
  bool paused() const { return paused_.load(); }
  // Notified after every snapshot publication (and when a render stops), from a worker thread.
  void setPublishSignal(std::shared_ptr<PublishSignal> s) { signal_ = std::move(s); }
  // Scheduling priority (Linux nice value, 0..19) of the worker threads of later start() / extend()
  // calls. An interactive viewer raises it so that its UI thread, which needs a few ms now and then,
  // gets a core at once instead of a fair share beside the workers; alone, they run as fast as ever.
  void setWorkerNice(int nice) { workerNice_ = nice; }

  RenderProgress progress() const;
  // Asks the workers to publish a snapshot at the next pass boundary (cheap to call every frame).
  // While requests keep coming (one within the last two passes), every pass is resolved row by row by
  // the worker that rendered the row, while its sums are still in cache, and published at the pass
  // boundary without stopping the other workers; otherwise the last worker resolves the whole film at
  // the boundary. Interactive starts (RenderLimits::preview) resolve their first pass this way too.
  void requestSnapshot(bool withStandardError = false);
  // The pixel whose statistics each published snapshot carries (FilmSnapshot::probe); x < 0: none.
  void setProbePixel(int x, int y);
  // That pixel's statistics now, if the film is at rest (paused at a pass boundary, or finished and
  // joined); false otherwise.
  bool probeAtRest(int x, int y, FilmSnapshot::Probe& out);
  // While paused at a pass boundary, publishes that pass if it was not (no snapshot was requested
  // when it ended) or lacks a requested standard error, so a viewer shows what the film holds. False
  // when not resting or already published.
  bool publishAtRest();
  // Copies the latest published snapshot into `out` if it is newer than out.version.
  bool latestSnapshot(FilmSnapshot& out) const;
  // The same for the engine's only reader, without copying the images: swaps them with out's (the
  // engine reuses out's old buffers for later snapshots). Afterwards latestSnapshot() must not be used.
  bool takeSnapshot(FilmSnapshot& out);

  // Valid once the render has stopped (after wait() or cancel()).
  const Film& film() const { return film_; }
  std::shared_ptr<const RenderJob> job() const { return job_; }
  int threadCount() const { return threadCount_; }  // of the current or last render

 private:
  void spawnWorkers(bool preview);
  void workerLoop(int workerIndex, bool preview);
  bool passBoundary();  // run by the last worker to finish a pass; returns true to stop
  void publishSnapshot();
  void publishResolved();
  void stampSnapshot(uint32_t spp, bool withError);
  void prepareResolve(bool mean, bool error);
  double elapsedNow() const;

  std::shared_ptr<const RenderJob> job_;
  RenderLimits limits_;
  Film film_;
  std::vector<std::thread> workers_;

  // Pass state.
  std::atomic<int> nextRow_{0};
  std::atomic<bool> cancel_{false};
  std::atomic<bool> stopRequested_{false};
  std::atomic<bool> finished_{true};
  std::atomic<bool> paused_{false};
  bool restingAtBoundary_ = false;           // under passMutex_: a worker waits paused at a pass boundary
  std::atomic<uint64_t> probePixel_{~0ull};  // (x << 32) | y, ~0: none
  std::atomic<uint32_t> spp_{0};
  std::atomic<uint64_t> badSamples_{0};
  uint32_t pass_ = 0;
  std::atomic<int> nextPreviewRow_{0};
  Image preview_;
  int arrived_ = 0;
  uint64_t generation_ = 0;
  bool stopAll_ = false;
  int threadCount_ = 0;
  int workerNice_ = 0;
  std::shared_ptr<PublishSignal> signal_;
  mutable std::mutex passMutex_;
  std::condition_variable passCv_;

  // Time accounting (seconds since start, pauses excluded).
  std::chrono::steady_clock::time_point startTime_;
  std::atomic<double> pausedSeconds_{0.0};
  std::chrono::steady_clock::time_point pauseBegan_;
  std::atomic<double> finalSeconds_{0.0};
  std::atomic<double> passSeconds_{0.0};  // written before spp_ at each boundary (see progress())
  double cpuAtStart_ = 0.0;

  // Snapshot publishing.
  std::atomic<bool> snapshotRequested_{false};
  std::atomic<bool> snapshotWantsError_{false};
  std::atomic<uint64_t> requests_{0}, errorRequests_{0};
  uint64_t requestsSeen_[2] = {0, 0}, errorRequestsSeen_[2] = {0, 0};  // at the last two boundaries
  bool published_ = false;  // by the pass boundary being run (notify signal_ once it is over)
  bool resolveMean_ = false, resolveError_ = false;  // the current pass resolves its rows into:
  Image pendingMean_, pendingError_;
  mutable std::mutex snapshotMutex_;
  FilmSnapshot snapshot_;
  bool publishedError_ = false;  // snapshot_ was published with its standard error (snapshotMutex_)
};

}  // namespace penumbra
