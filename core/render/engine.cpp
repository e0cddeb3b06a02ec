#include "core/render/engine.h"

#include <algorithm>
#include <chrono>
#include <system_error>
#include <thread>

#include "core/math/error.h"
#include "core/render/row_renderer.h"

namespace penumbra {

Engine::~Engine() {
  cancel();
}

void Engine::start(std::shared_ptr<const RenderJob> job, RenderLimits limits, int threads,
                   SampleSchedule schedule) {
  cancel();
  job_ = std::move(job);
  limits_ = limits;
  schedule_ = schedule;
  const CameraDesc& cam = job_->settings.camera;
  if (film_.width() != cam.width || film_.height() != cam.height)
    film_.reset(cam.width, cam.height);
  else
    film_.clear();

  if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
  nextRow_ = 0;
  passRowsDone_ = 0;
  cancel_ = false;
  stopRequested_ = false;
  stopNow_ = false;
  abandonRows_ = false;
  rowsAhead_ = false;
  rollBackRows_ = rollbackMode_ != RowRollback::Never;
  rowPasses_.assign(size_t(std::max(cam.height, 0)), 0);
  finished_ = false;
  spp_ = 0;
  passSeconds_ = 0.0;
  badSamples_ = 0;
  {
    PassBarrier::Lock lk = barrier_.lock();
    failure_ = nullptr;
  }
  clock_.start();
  publisher_.restart();
  spawnWorkers(threads, limits.preview);
}

void Engine::spawnWorkers(int threads, bool preview) {
  barrier_.reset(threads);
  stopAll_ = false;
  nextPreviewRow_ = 0;
  try {
    // An interactive start shows its first pass at once; a one-pass render's image is resolved as it goes.
    publisher_.resolveNextPassRows(preview || nextPassIsLast(), film_);
    if (preview) preview_ = Image(film_.width(), film_.height());
    workers_.spawn(
        threads, [this, preview] { workerLoop(preview); }, [this](std::exception_ptr e) { workerFailed(e); });
  } catch (const std::system_error& e) {
    cancel();  // the workers already started would wait for the others at the first boundary
    throw Error("render: cannot start " + std::to_string(threads) + " worker threads (" + e.what() +
                "); ask for fewer threads");
  } catch (...) {
    cancel();
    throw;
  }
}

bool Engine::extend(RenderLimits limits) {
  if (!job_) return false;
  limits.preview = false;
  PassBarrier::Lock lk = barrier_.lock();
  if (!finished_) {
    limits_ = limits;  // read by passBoundary() under the barrier's lock
    return true;
  }
  // A cancelled pass left the film incomplete; rows ahead of the others would get a pass twice.
  if (cancel_ || rowsAhead_ || spp_ == 0) return false;
  lk.unlock();
  wait();  // join the idle workers
  limits_ = limits;
  if (limits_.targetSpp > 0 && spp_ >= limits_.targetSpp) return true;  // nothing more to do
  stopRequested_ = false;
  stopNow_ = false;
  abandonRows_ = false;
  if (rollbackMode_ != RowRollback::Auto) rollBackRows_ = rollbackMode_ == RowRollback::Always;
  clock_.resume();
  nextRow_ = 0;
  passRowsDone_ = 0;
  finished_ = false;
  spawnWorkers(workers_.size(), false);
  return true;
}

void Engine::finish() {
  if (!finished_.exchange(true)) clock_.stop();
}

void Engine::cancel() {
  cancel_ = true;
  abandonRows_ = true;
  {
    PassBarrier::Lock lk = barrier_.lock();
    barrier_.notifyAll();
  }
  workers_.join();
  finish();
}

void Engine::requestStop() {
  stopRequested_ = true;
  PassBarrier::Lock lk = barrier_.lock();
  barrier_.notifyAll();
}

void Engine::stopNow() {
  stopNow_ = true;
  abandonRows_ = true;
  PassBarrier::Lock lk = barrier_.lock();
  barrier_.notifyAll();
}

void Engine::wait() {
  workers_.join();
  if (std::exception_ptr e = failure()) std::rethrow_exception(e);
}

std::exception_ptr Engine::failure() const {
  PassBarrier::Lock lk = barrier_.lock();
  return failure_;
}

// Ends the render as cancel() does, from the failing worker: the others leave their rows within a
// pixel and the barrier (its waits give up once cancel_ is set), so none waits for this one.
void Engine::workerFailed(std::exception_ptr e) {
  {
    PassBarrier::Lock lk = barrier_.lock();
    if (!failure_) failure_ = e;
    cancel_ = true;
    abandonRows_ = true;
    finish();  // under the lock, as at a boundary: the clock's pause state is read
    barrier_.notifyAll();
  }
  if (signal_) signal_->notify();
}

void Engine::setPaused(bool paused) {
  PassBarrier::Lock lk = barrier_.lock();
  if (clock_.setPaused(paused, /*counting=*/!finished_)) barrier_.notifyAll();
}

RenderProgress Engine::progress() const {
  RenderProgress p;
  // passSeconds_ is written before spp_: re-read until both belong to the same boundary.
  do {
    p.spp = spp_;
    p.passSeconds = passSeconds_;
  } while (p.spp != spp_);
  p.finished = finished_;
  p.seconds = p.finished ? clock_.stoppedSeconds() : clock_.elapsed();
  p.samples = uint64_t(p.spp) * uint64_t(std::max(film_.width(), 0)) * uint64_t(std::max(film_.height(), 0));
  p.badSamples = badSamples_;
  p.resolveSeconds = double(resolveNanos_.load(std::memory_order_relaxed)) * 1e-9;
  p.rows = uint32_t(std::max(film_.height(), 0));
  p.passRows = p.finished ? 0u : std::min(uint32_t(std::max(passRowsDone_.load(), 0)), p.rows);
  return p;
}

bool Engine::probeAtRest(int x, int y, FilmSnapshot::Probe& out) {
  if (x < 0 || y < 0) return false;
  PassBarrier::Lock lk = barrier_.lock();
  if (!restingAtBoundary_ && !finished_) return false;  // finished under the lock: no worker writes
  filmProbe(film_, spp_, x, y, out);
  return out.x >= 0;
}

bool Engine::publishAtRest() {
  PassBarrier::Lock lk = barrier_.lock();
  if (!restingAtBoundary_) return false;
  if (!publisher_.publishIfStale(film_, spp_)) return false;
  if (signal_) signal_->notify();
  return true;
}

// Runs in the last worker to finish a pass, with the barrier's lock held and every other worker waiting.
bool Engine::passBoundary() {
  if (cancel_) return true;
  if (stopNow_) {
    // The pass counts only if every row completed it; otherwise the rows that did are ahead.
    const size_t completed = size_t(std::count(rowPasses_.begin(), rowPasses_.end(), spp_ + 1));
    if (completed < rowPasses_.size()) {
      rowsAhead_ = completed > 0;
      return true;
    }
  }
  const double now = clock_.elapsed();
  if (rollbackMode_ == RowRollback::Auto) {
    const double rowSeconds = (now - passSeconds_) * workers_.size() / std::max(1, film_.height());
    rollBackRows_ = rowSeconds > kRollBackRowSeconds;
  }
  passSeconds_ = now;
  passRowsDone_ = 0;
  spp_ = spp_ + 1;
  nextRow_ = 0;
  const bool stop = stopRequested_ || stopNow_ || (limits_.targetSpp > 0 && spp_ >= limits_.targetSpp) ||
                    (limits_.seconds > 0 && clock_.elapsed() >= limits_.seconds);
  // Finished before the last pass is published: a viewer that sees the final image sees it finished.
  if (stop) finish();
  // The last pass is always published, so viewers see the finished image.
  const bool published = publisher_.atPassBoundary(film_, spp_, stop, !stop && nextPassIsLast());
  if (signal_ && published && !stop) signal_->notify();
  return stop;
}

// One sample per block, written over the whole block; the film is untouched. Published once every
// worker is done with it.
void Engine::renderPreview(const RowRenderer& renderRow, Sampler& sampler) {
  const int height = film_.height();
  const int blockRows = (height + kPreviewBlock - 1) / kPreviewBlock;
  for (int b;
       !abandonRows_.load(std::memory_order_relaxed) && (b = nextPreviewRow_.fetch_add(1)) < blockRows;)
    renderRow.preview(b * kPreviewBlock, kPreviewBlock, sampler, preview_, abandonRows_);
  PassBarrier::Lock lk = barrier_.lock();
  if (barrier_.arrive(lk, [&] { return cancel_.load(); })) {
    if (!cancel_) {
      publisher_.publishPreview(std::move(preview_));  // the preview is done with
      if (signal_) signal_->notify();
    }
    barrier_.release();
  }
}

void Engine::workerLoop(bool preview) {
  const RenderJob& job = *job_;
  const RenderSettings& s = job.settings;
  RowRenderer renderRow = rowRendererFactory_ ? rowRendererFactory_(job) : makeRowRenderer(job);
  Sampler sampler(s.samplerKind, s.sampleCount, s.seed);
  const int height = s.camera.height;
  const size_t rowValues = size_t(s.camera.width) * 6;
  std::vector<double> rowBefore(rowValues);  // the sums of this worker's row before its pass

  if (preview) renderPreview(renderRow, sampler);

  uint32_t pass = spp_;
  Image* meanRows = publisher_.rowMeanTarget();
  Image* errorRows = publisher_.rowErrorTarget();
  for (;;) {
    const uint32_t sampleIndex = uint32_t(schedule_.sampleIndex(pass));
    uint64_t bad = 0;
    const bool rollback = rollBackRows_.load(std::memory_order_relaxed);
    for (int y; !abandonRows_.load(std::memory_order_relaxed) && (y = nextRow_.fetch_add(1)) < height;) {
      double* sums = film_.sums().data() + size_t(y) * rowValues;
      if (rollback) std::copy(sums, sums + rowValues, rowBefore.begin());
      const uint64_t badBefore = bad;
      renderRow.row(y, sampleIndex, sampler, film_, bad, rollback ? abandonRows_ : cancel_);
      // A row returns early only once its flag is set, so a row seen unflagged here is complete; a
      // flagged one is rolled back whether or not it completed. Without the copy only cancel() leaves
      // a row unfinished (and the pass with it).
      if (rollback && abandonRows_.load(std::memory_order_relaxed)) {
        std::copy(rowBefore.begin(), rowBefore.end(), sums);
        bad = badBefore;
        break;
      }
      if (cancel_.load(std::memory_order_relaxed)) break;
      rowPasses_[size_t(y)] = pass + 1;
      passRowsDone_.fetch_add(1, std::memory_order_relaxed);
      // This worker owns row y until the pass ends: resolve it now, from sums still in cache.
      if (meanRows || errorRows) {
        const auto resolveStart = std::chrono::steady_clock::now();
        if (meanRows) film_.resolveMean(pass + 1, *meanRows, y, y + 1);
        if (errorRows) film_.resolveStandardError(pass + 1, *errorRows, y, y + 1);
        resolveNanos_.fetch_add(uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                             std::chrono::steady_clock::now() - resolveStart)
                                             .count()),
                                std::memory_order_relaxed);
      }
    }
    if (bad) badSamples_ += bad;

    PassBarrier::Lock lk = barrier_.lock();
    // A cancelled render (or a failed worker, which may never arrive) ends here without the boundary.
    if (barrier_.arrive(lk, [&] { return cancel_.load(); })) {
      bool stop = passBoundary();
      restingAtBoundary_ = true;  // the film is at rest while this worker waits (probeAtRest)
      if (!stop) barrier_.wait(lk, [&] { return !clock_.paused() || cancel_ || stopRequested_ || stopNow_; });
      restingAtBoundary_ = false;
      if (!stop && (cancel_ || stopRequested_ || stopNow_)) stop = true;
      if (stop) finish();
      if (signal_ && stop) signal_->notify();  // after `finished`, which viewers read
      stopAll_ = stop;
      barrier_.release();
    }
    if (stopAll_ || cancel_) return;
    pass = spp_;
    meanRows = publisher_.rowMeanTarget();
    errorRows = publisher_.rowErrorTarget();
  }
}

}  // namespace penumbra
