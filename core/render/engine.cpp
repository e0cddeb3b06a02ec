#include "core/render/engine.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <ctime>

#include "core/render/row_renderer.h"

namespace penumbra {

double processCpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

void PublishSignal::notify() {
  {
    std::lock_guard lk(mutex_);
    ++count_;
  }
  cv_.notify_all();
}

uint64_t PublishSignal::count() const {
  std::lock_guard lk(mutex_);
  return count_;
}

uint64_t PublishSignal::wait(uint64_t seen, double seconds) const {
  std::unique_lock lk(mutex_);
  cv_.wait_for(lk, std::chrono::duration<double>(seconds), [&] { return count_ != seen; });
  return count_;
}

Engine::~Engine() {
  cancel();
}

void Engine::start(std::shared_ptr<const RenderJob> job, RenderLimits limits, int threads) {
  cancel();
  job_ = std::move(job);
  limits_ = limits;
  const CameraDesc& cam = job_->settings.camera;
  if (film_.width() != cam.width || film_.height() != cam.height)
    film_.reset(cam.width, cam.height);
  else
    film_.clear();

  if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
  nextRow_ = 0;
  cancel_ = false;
  stopRequested_ = false;
  finished_ = false;
  spp_ = 0;
  badSamples_ = 0;
  pass_ = 0;
  arrived_ = 0;
  stopAll_ = false;
  threadCount_ = threads;
  pausedSeconds_ = 0.0;
  finalSeconds_ = 0.0;
  passSeconds_ = 0.0;
  startTime_ = std::chrono::steady_clock::now();
  cpuAtStart_ = processCpuSeconds();
  pauseBegan_ = startTime_;
  {
    std::lock_guard lk(snapshotMutex_);
    snapshot_.spp = 0;
    snapshot_.seconds = 0;
    snapshot_.cpuSeconds = 0;
    ++snapshot_.version;  // viewers see the restart at once
    snapshot_.mean = Image();
    snapshot_.standardError = Image();
  }
  spawnWorkers(limits.preview);
}

void Engine::spawnWorkers(bool preview) {
  arrived_ = 0;
  stopAll_ = false;
  nextPreviewRow_ = 0;
  prepareResolve(preview, false);  // an interactive start shows its first pass as soon as it ends
  if (preview) {
    const CameraDesc& cam = job_->settings.camera;
    preview_ = Image(cam.width, cam.height);
  }
  workers_.reserve(threadCount_);
  for (int i = 0; i < threadCount_; ++i)
    workers_.emplace_back([this, i, preview] { workerLoop(i, preview); });
}

bool Engine::extend(RenderLimits limits) {
  if (!job_) return false;
  limits.preview = false;
  std::unique_lock lk(passMutex_);
  if (!finished_) {
    limits_ = limits;  // read by passBoundary() under passMutex_
    return true;
  }
  if (cancel_ || spp_ == 0) return false;  // a cancelled pass left the film incomplete
  lk.unlock();
  wait();  // join the idle workers
  limits_ = limits;
  if (limits_.targetSpp > 0 && spp_ >= limits_.targetSpp) return true;  // nothing more to do
  stopRequested_ = false;
  // Resume the clock where it stopped.
  startTime_ =
      std::chrono::steady_clock::now() - std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                             std::chrono::duration<double>(finalSeconds_.load()));
  pausedSeconds_ = 0.0;
  nextRow_ = 0;
  finished_ = false;
  spawnWorkers(false);
  return true;
}

void Engine::cancel() {
  cancel_ = true;
  {
    std::lock_guard lk(passMutex_);
    passCv_.notify_all();
  }
  for (std::thread& t : workers_) t.join();
  workers_.clear();
  if (!finished_.exchange(true)) finalSeconds_ = elapsedNow();
}

void Engine::requestStop() {
  stopRequested_ = true;
  std::lock_guard lk(passMutex_);
  passCv_.notify_all();
}

void Engine::wait() {
  for (std::thread& t : workers_) t.join();
  workers_.clear();
}

void Engine::setPaused(bool paused) {
  std::lock_guard lk(passMutex_);
  if (paused == paused_.load()) return;
  auto now = std::chrono::steady_clock::now();
  if (paused)
    pauseBegan_ = now;
  else if (!finished_)
    pausedSeconds_ = pausedSeconds_ + std::chrono::duration<double>(now - pauseBegan_).count();
  paused_ = paused;
  passCv_.notify_all();
}

double Engine::elapsedNow() const {
  auto now = paused_ ? pauseBegan_ : std::chrono::steady_clock::now();
  return std::chrono::duration<double>(now - startTime_).count() - pausedSeconds_;
}

RenderProgress Engine::progress() const {
  RenderProgress p;
  // passSeconds_ is written before spp_: re-read until both belong to the same boundary.
  do {
    p.spp = spp_;
    p.passSeconds = passSeconds_;
  } while (p.spp != spp_);
  p.finished = finished_;
  p.seconds = p.finished ? finalSeconds_.load() : elapsedNow();
  p.samples = uint64_t(p.spp) * uint64_t(std::max(film_.width(), 0)) * uint64_t(std::max(film_.height(), 0));
  p.badSamples = badSamples_;
  return p;
}

// A pixel as one atomic word: (x << 32) | y; ~0 for none.
static uint64_t packPixel(int x, int y) {
  return x < 0 || y < 0 ? ~0ull : (uint64_t(uint32_t(x)) << 32) | uint32_t(y);
}

void Engine::setProbePixel(int x, int y) {
  probePixel_ = packPixel(x, y);
}

// The probe pixel's statistics from the film, which must be at rest (a pass boundary).
static void fillProbe(const Film& film, uint32_t spp, uint64_t packed, FilmSnapshot::Probe& probe) {
  probe = FilmSnapshot::Probe();
  if (packed == ~0ull) return;
  const int x = int(packed >> 32), y = int(uint32_t(packed));
  if (x >= film.width() || y >= film.height()) return;
  probe.x = x, probe.y = y;
  film.pixelStatistics(spp, x, y, probe.mean, probe.standardError);
}

bool Engine::probeAtRest(int x, int y, FilmSnapshot::Probe& out) {
  if (x < 0 || y < 0) return false;
  std::lock_guard lk(passMutex_);
  if (!restingAtBoundary_ && !finished_) return false;  // finished under passMutex_: no worker writes
  fillProbe(film_, spp_, packPixel(x, y), out);
  return out.x >= 0;
}

bool Engine::publishAtRest() {
  std::lock_guard lk(passMutex_);
  if (!restingAtBoundary_) return false;
  {
    // By what was published, not by snapshot_'s images: takeSnapshot swaps those with old buffers.
    std::lock_guard sl(snapshotMutex_);
    const bool errorMissing = snapshotWantsError_ && !publishedError_ && spp_ >= 2;
    if (snapshot_.spp == spp_ && !errorMissing) return false;
  }
  publishSnapshot();
  if (signal_) signal_->notify();
  return true;
}

void Engine::requestSnapshot(bool withStandardError) {
  if (withStandardError) {
    snapshotWantsError_ = true;
    ++errorRequests_;
  }
  ++requests_;
  snapshotRequested_ = true;
}

void Engine::prepareResolve(bool mean, bool error) {
  resolveMean_ = mean;
  resolveError_ = mean && error;
  const CameraDesc& cam = job_->settings.camera;
  if (resolveMean_ && (pendingMean_.width != cam.width || pendingMean_.height != cam.height))
    pendingMean_ = Image(cam.width, cam.height);
  if (resolveError_ && (pendingError_.width != cam.width || pendingError_.height != cam.height))
    pendingError_ = Image(cam.width, cam.height);
}

// The pass that just ended was resolved row by row into pendingMean_ (and pendingError_): publish it
// by swapping buffers (the old snapshot's become the next pass's pending ones; readers copy).
void Engine::publishResolved() {
  std::lock_guard lk(snapshotMutex_);
  std::swap(snapshot_.mean, pendingMean_);
  if (resolveError_) {
    std::swap(snapshot_.standardError, pendingError_);
    snapshotWantsError_ = false;
  } else {
    snapshot_.standardError = Image();
  }
  stampSnapshot(spp_, resolveError_);
}

// The rest of a publication, under snapshotMutex_, once the images are in place.
void Engine::stampSnapshot(uint32_t spp, bool withError) {
  snapshot_.spp = spp;
  publishedError_ = withError;
  if (spp > 0)
    fillProbe(film_, spp, probePixel_, snapshot_.probe);
  else
    snapshot_.probe = FilmSnapshot::Probe();  // the preview: no pass yet
  snapshot_.seconds = elapsedNow();
  snapshot_.cpuSeconds = processCpuSeconds() - cpuAtStart_;
  ++snapshot_.version;
}

bool Engine::latestSnapshot(FilmSnapshot& out) const {
  std::lock_guard lk(snapshotMutex_);
  if (snapshot_.version == out.version) return false;
  out = snapshot_;
  return true;
}

bool Engine::takeSnapshot(FilmSnapshot& out) {
  std::lock_guard lk(snapshotMutex_);
  if (snapshot_.version == out.version) return false;
  std::swap(out.mean, snapshot_.mean);
  std::swap(out.standardError, snapshot_.standardError);
  out.version = snapshot_.version;
  out.spp = snapshot_.spp;
  out.seconds = snapshot_.seconds;
  out.cpuSeconds = snapshot_.cpuSeconds;
  out.probe = snapshot_.probe;
  return true;
}

void Engine::publishSnapshot() {
  uint32_t spp = spp_;
  bool withError = snapshotWantsError_.exchange(false);
  Image mean = film_.mean(spp);
  Image err;
  if (withError) err = film_.standardError(spp);
  std::lock_guard lk(snapshotMutex_);
  snapshot_.mean = std::move(mean);
  snapshot_.standardError = std::move(err);
  stampSnapshot(spp, withError);
}

// Runs in the last worker to finish a pass, with passMutex_ held and every other worker waiting.
bool Engine::passBoundary() {
  if (cancel_) return true;
  passSeconds_ = elapsedNow();
  spp_ = spp_ + 1;
  ++pass_;
  nextRow_ = 0;
  bool stop = stopRequested_ || (limits_.targetSpp > 0 && spp_ >= limits_.targetSpp) ||
              (limits_.seconds > 0 && elapsedNow() >= limits_.seconds);
  // The last pass is always published, so viewers see the finished image.
  bool requested = snapshotRequested_.exchange(false);
  published_ = resolveMean_ || requested || stop;  // notified by the caller
  if (resolveMean_)
    publishResolved();
  else if (requested || stop)
    publishSnapshot();
  // Resolve the next pass row by row while requests keep coming (one since either of the last two
  // boundaries): a viewer asks again right after it fetched a snapshot, i.e. early in the next pass.
  const uint64_t r = requests_, e = errorRequests_;
  bool mean = !stop && (r != requestsSeen_[0] || requestsSeen_[0] != requestsSeen_[1]);
  bool error = e != errorRequestsSeen_[0] || errorRequestsSeen_[0] != errorRequestsSeen_[1];
  requestsSeen_[1] = requestsSeen_[0], requestsSeen_[0] = r;
  errorRequestsSeen_[1] = errorRequestsSeen_[0], errorRequestsSeen_[0] = e;
  prepareResolve(mean, error);
  return stop;
}

void Engine::workerLoop(int /*workerIndex*/, bool preview) {
  // Linux: a nice value set through the thread id applies to this thread only.
  if (workerNice_ > 0) setpriority(PRIO_PROCESS, id_t(syscall(SYS_gettid)), workerNice_);
  const RenderJob& job = *job_;
  const RenderSettings& s = job.settings;
  RowRenderer renderRow = makeRowRenderer(job);
  Sampler sampler(s.samplerKind, s.sampleCount, s.seed);
  const int height = s.camera.height;
  const int threadCount = threadCount_;

  if (preview) {
    // One sample per block, written over the whole block; the film is untouched.
    const int blockRows = (height + kPreviewBlock - 1) / kPreviewBlock;
    for (int b; !cancel_.load(std::memory_order_relaxed) && (b = nextPreviewRow_.fetch_add(1)) < blockRows;)
      renderRow.preview(b * kPreviewBlock, kPreviewBlock, sampler, preview_);
    std::unique_lock lk(passMutex_);
    if (++arrived_ == threadCount) {
      arrived_ = 0;
      if (!cancel_) {
        std::lock_guard sl(snapshotMutex_);
        snapshot_.mean = std::move(preview_);  // the preview is done with
        snapshot_.standardError = Image();
        stampSnapshot(0, false);
      }
      if (signal_ && !cancel_) signal_->notify();
      ++generation_;
      passCv_.notify_all();
    } else {
      uint64_t generation = generation_;
      passCv_.wait(lk, [&] { return generation_ != generation || cancel_.load(); });
    }
  }

  uint32_t pass = pass_;
  bool resolveMean = resolveMean_, resolveError = resolveError_;
  for (;;) {
    uint64_t bad = 0;
    for (int y; !cancel_.load(std::memory_order_relaxed) && (y = nextRow_.fetch_add(1)) < height;) {
      renderRow.row(y, pass, sampler, film_, bad, cancel_);
      // This worker owns row y until the pass ends: resolve it now, from sums still in cache.
      if (resolveMean) film_.resolveMean(pass + 1, pendingMean_, y, y + 1);
      if (resolveError) film_.resolveStandardError(pass + 1, pendingError_, y, y + 1);
    }
    if (bad) badSamples_ += bad;

    std::unique_lock lk(passMutex_);
    uint64_t generation = generation_;
    if (++arrived_ == threadCount) {
      arrived_ = 0;
      bool stop = passBoundary();
      if (signal_ && published_ && !stop) signal_->notify();
      restingAtBoundary_ = true;  // the film is at rest while this worker waits (probeAtRest)
      while (!stop && paused_ && !cancel_ && !stopRequested_) passCv_.wait(lk);
      restingAtBoundary_ = false;
      if (!stop && (cancel_ || stopRequested_)) stop = true;
      if (stop && !finished_.exchange(true)) finalSeconds_ = elapsedNow();
      if (signal_ && stop) signal_->notify();  // after `finished`, which viewers read
      stopAll_ = stop;
      ++generation_;
      passCv_.notify_all();
    } else {
      passCv_.wait(lk, [&] { return generation_ != generation; });
    }
    if (stopAll_) return;
    pass = pass_;
    resolveMean = resolveMean_, resolveError = resolveError_;
  }
}

}  // namespace penumbra
