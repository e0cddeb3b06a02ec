#include "core/render/engine.h"

#include <algorithm>
#include <ctime>

#include "core/render/row_renderer.h"

namespace penumbra {

namespace {
double processCpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}
}  // namespace

Engine::~Engine() { cancel(); }

void Engine::start(std::shared_ptr<const RenderJob> job, RenderLimits limits, int threads) {
  cancel();
  job_ = std::move(job);
  limits_ = limits;
  const CameraDesc& cam = job_->settings.camera;
  if (film_.width() != cam.width || film_.height() != cam.height) film_.reset(cam.width, cam.height);
  else film_.clear();

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
  workers_.reserve(threads);
  for (int i = 0; i < threads; ++i) workers_.emplace_back([this, i] { workerLoop(i); });
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
  if (paused) pauseBegan_ = now;
  else if (!finished_) pausedSeconds_ = pausedSeconds_ + std::chrono::duration<double>(now - pauseBegan_).count();
  paused_ = paused;
  passCv_.notify_all();
}

double Engine::elapsedNow() const {
  auto now = paused_ ? pauseBegan_ : std::chrono::steady_clock::now();
  return std::chrono::duration<double>(now - startTime_).count() - pausedSeconds_;
}

RenderProgress Engine::progress() const {
  RenderProgress p;
  p.spp = spp_;
  p.finished = finished_;
  p.seconds = p.finished ? finalSeconds_.load() : elapsedNow();
  p.samples = uint64_t(p.spp) * uint64_t(std::max(film_.width(), 0)) * uint64_t(std::max(film_.height(), 0));
  p.badSamples = badSamples_;
  return p;
}

void Engine::requestSnapshot(bool withStandardError) {
  if (withStandardError) snapshotWantsError_ = true;
  snapshotRequested_ = true;
}

bool Engine::latestSnapshot(FilmSnapshot& out) const {
  std::lock_guard lk(snapshotMutex_);
  if (snapshot_.version == out.version) return false;
  out = snapshot_;
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
  snapshot_.spp = spp;
  snapshot_.seconds = elapsedNow();
  snapshot_.cpuSeconds = processCpuSeconds() - cpuAtStart_;
  ++snapshot_.version;
}

// Runs in the last worker to finish a pass, with passMutex_ held and every other worker waiting.
bool Engine::passBoundary() {
  if (cancel_) return true;
  spp_ = spp_ + 1;
  ++pass_;
  nextRow_ = 0;
  if (snapshotRequested_.exchange(false)) publishSnapshot();
  if (stopRequested_) return true;
  if (limits_.targetSpp > 0 && spp_ >= limits_.targetSpp) return true;
  if (limits_.seconds > 0 && elapsedNow() >= limits_.seconds) return true;
  return false;
}

void Engine::workerLoop(int /*workerIndex*/) {
  const RenderJob& job = *job_;
  const RenderSettings& s = job.settings;
  RowRenderer renderRow = makeRowRenderer(job);
  Sampler sampler(s.samplerKind, s.sampleCount, s.seed);
  const int height = s.camera.height;
  const int threadCount = threadCount_;

  uint32_t pass = 0;
  for (;;) {
    uint64_t bad = 0;
    for (int y; !cancel_.load(std::memory_order_relaxed) && (y = nextRow_.fetch_add(1)) < height;)
      renderRow(y, pass, sampler, film_, bad);
    if (bad) badSamples_ += bad;

    std::unique_lock lk(passMutex_);
    uint64_t generation = generation_;
    if (++arrived_ == threadCount) {
      arrived_ = 0;
      bool stop = passBoundary();
      while (!stop && paused_ && !cancel_ && !stopRequested_) passCv_.wait(lk);
      if (!stop && (cancel_ || stopRequested_)) stop = true;
      if (stop && !finished_.exchange(true)) finalSeconds_ = elapsedNow();
      stopAll_ = stop;
      ++generation_;
      passCv_.notify_all();
    } else {
      passCv_.wait(lk, [&] { return generation_ != generation; });
    }
    if (stopAll_) return;
    pass = pass_;
  }
}

}  // namespace penumbra
