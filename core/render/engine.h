// Progressive renderer: whole-image passes of one sample per pixel on a pool of worker threads.
// Pass p uses sample index p in every pixel (or the index a SampleSchedule gives it), so the image
// depends only on (scene, settings, seed), never on thread count or scheduling. Cancellation takes effect
// within one pixel (its samples; a batch of AO samples, about a thousand rays, in Embree scenes). stopNow()
// ends a render as fast, keeping the rows that completed the running pass, so that every row holds whole
// passes (rowPasses()): a worker either finishes its row or, where rows are expensive, restores the row's
// sums from a copy taken before the row.
//
// The engine schedules passes; its parts keep the rest: WorkerPool (threads and their priority),
// PassBarrier (the workers' meeting at each pass boundary), RenderClock (time with pauses excluded,
// CPU time), SnapshotPublisher (what readers see, and how passes are resolved for them).
#pragma once

#include <atomic>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <vector>

#include "core/image/image.h"
#include "core/render/film.h"
#include "core/render/pass_barrier.h"
#include "core/render/publish_signal.h"
#include "core/render/render_clock.h"
#include "core/render/render_job.h"
#include "core/render/row_renderer.h"
#include "core/render/sample_schedule.h"
#include "core/render/snapshot_publisher.h"
#include "core/render/worker_pool.h"

namespace penumbra {

struct RenderProgress {
  uint32_t spp = 0;          // completed passes
  double seconds = 0.0;      // rendering time, pauses excluded
  double passSeconds = 0.0;  // rendering time when pass `spp` completed (rates independent of polling)
  uint64_t samples = 0;      // camera samples accumulated
  uint64_t badSamples = 0;   // NaN, Inf or negative values (dropped and counted)
  bool finished = false;
  // Progress within the running pass (a slow pass shows it): rows of the image that completed pass
  // spp + 1 so far, of `rows`. 0 once finished.
  uint32_t passRows = 0;
  uint32_t rows = 0;
  // Worker time spent resolving rows for snapshots over the engine's life (what showing passes costs
  // the workers; a viewer budgets it with its own frames).
  double resolveSeconds = 0.0;
};

class Engine {
 public:
  Engine() = default;
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  // Starts a fresh accumulation (cancelling any running one). threads <= 0: all cores. `schedule`
  // maps passes to sample indices for the whole accumulation (extend keeps it). Throws (nothing
  // left running) when the film cannot be allocated or the threads cannot be started.
  void start(std::shared_ptr<const RenderJob> job, RenderLimits limits = {}, int threads = 0,
             SampleSchedule schedule = {});
  // Abandons the running pass and joins the workers; the film keeps the completed passes.
  void cancel();
  // Finishes the current pass, then stops (what Ctrl-C in `penumbra render` does).
  void requestStop();
  // Stops inside the running pass without losing exactness: the rows that completed the pass keep it,
  // the others never started it or are rolled back. Rows being rendered are finished when rows are
  // cheap, or abandoned within a pixel and restored from a copy of their sums taken before the row
  // (RowRollback). Afterwards progress().spp counts the passes every row has, and rowPasses() says
  // which rows have one more. A render with such extra rows cannot be extended.
  void stopNow();
  // Whether workers copy each row's sums before rendering it, so that stopNow() can abandon the row
  // within a pixel. The copy costs ~4 % of the render on the cheapest scenes (the hw2 sphere scene:
  // 48 bytes per pixel sample beside ~65 ns of rendering), so Auto takes it only in passes whose rows
  // took over kRollBackRowSeconds in the pass before (the first pass always): a cheaper row is
  // finished instead, in at most that long. For start() and extend() calls after it.
  enum class RowRollback { Auto, Always, Never };
  static constexpr double kRollBackRowSeconds = 0.005;
  void setRowRollback(RowRollback mode) { rollbackMode_ = mode; }
  // Passes accumulated in each row of the film; valid once the render has stopped. All equal
  // progress().spp except, after stopNow(), the rows that completed the interrupted pass (spp + 1).
  const std::vector<uint32_t>& rowPasses() const { return rowPasses_; }
  // New limits for the current accumulation, without restarting it: a running render adopts them at
  // its next pass boundary; a render that stopped at its old limits resumes where it left off.
  // Returns false (and changes nothing) when there is no accumulation to extend.
  bool extend(RenderLimits limits);
  // Blocks until the limits are reached or the render is stopped. Rethrows, here on the calling
  // thread, the exception that made a worker fail (see failure()).
  void wait();
  // What a worker threw (std::bad_alloc resolving a snapshot, an integrator's error), or null. A
  // worker that throws ends the render as cancel() does: the other workers stop within a pixel, the
  // render is finished, and the film holds the completed passes plus part of the failed one. Reset
  // by start().
  std::exception_ptr failure() const;
  // The row renderer each worker makes at its start (default makeRowRenderer); tests substitute
  // one that fails. For later start() calls.
  void setRowRendererFactory(std::function<RowRenderer(const RenderJob&)> factory) {
    rowRendererFactory_ = std::move(factory);
  }
  void setPaused(bool paused);
  bool paused() const { return clock_.paused(); }
  // Notified after every snapshot publication (and when a render stops), from a worker thread.
  void setPublishSignal(std::shared_ptr<PublishSignal> s) { signal_ = std::move(s); }
  // Scheduling priority (Linux nice value, 0..19) of the worker threads of later start() / extend()
  // calls. An interactive viewer raises it so that its UI thread, which needs a few ms now and then,
  // gets a core at once instead of a fair share beside the workers; alone, they run as fast as ever.
  void setWorkerNice(int nice) { workers_.setNice(nice); }

  RenderProgress progress() const;
  // Asks the workers to publish a snapshot at the next pass boundary (cheap to call every frame).
  // While requests keep coming (one within the last two passes), every pass is resolved row by row by
  // the worker that rendered the row, while its sums are still in cache, and published at the pass
  // boundary without stopping the other workers; otherwise the last worker resolves the whole film at
  // the boundary. Interactive starts (RenderLimits::preview) resolve their first pass this way too.
  void requestSnapshot(bool withStandardError = false) { publisher_.request(withStandardError); }
  // For a reader that wants a snapshot now and then without holding up the workers (streaming to an
  // external viewer): the pass after the running one is resolved row by row as it renders and
  // published at its end (with its standard error if asked), and no later pass is. Unlike
  // requestSnapshot, no worker waits at a boundary for a serial resolve; the price is up to two
  // passes of latency.
  void requestNextPassSnapshot(bool withStandardError = false) {
    publisher_.requestNextPass(withStandardError);
  }
  // The pixel whose statistics each published snapshot carries (FilmSnapshot::probe); x < 0: none.
  void setProbePixel(int x, int y) { publisher_.setProbePixel(x, y); }
  // That pixel's statistics now, if the film is at rest (paused at a pass boundary, or finished and
  // joined); false otherwise.
  bool probeAtRest(int x, int y, FilmSnapshot::Probe& out);
  // While paused at a pass boundary, publishes that pass if it was not (no snapshot was requested
  // when it ended) or lacks a requested standard error, so a viewer shows what the film holds. False
  // when not resting or already published.
  bool publishAtRest();
  // Copies the latest published snapshot into `out` if it is newer than out.version.
  bool latestSnapshot(FilmSnapshot& out) const { return publisher_.latest(out); }
  // The same for the engine's only reader, without copying the images: swaps them with out's (the
  // engine reuses out's old buffers for later snapshots). Afterwards latestSnapshot() must not be used.
  bool takeSnapshot(FilmSnapshot& out) { return publisher_.take(out); }

  // Valid once the render has stopped (after wait() or cancel()).
  const Film& film() const { return film_; }
  std::shared_ptr<const RenderJob> job() const { return job_; }
  int threadCount() const { return workers_.size(); }  // of the current or last render

 private:
  void spawnWorkers(int threads, bool preview);
  void workerLoop(bool preview);
  void renderPreview(const RowRenderer& renderRow, Sampler& sampler);
  bool passBoundary();  // run by the last worker to finish a pass; returns true to stop
  bool nextPassIsLast() const { return limits_.targetSpp > 0 && spp_ + 1 >= limits_.targetSpp; }
  void finish();                            // marks the accumulation finished (once) and stops its clock
  void workerFailed(std::exception_ptr e);  // on the failing worker: keep e, stop the others

  std::shared_ptr<const RenderJob> job_;
  RenderLimits limits_;      // under the barrier's lock while workers run
  SampleSchedule schedule_;  // of the current accumulation: set by start() only
  Film film_;
  WorkerPool workers_;
  PassBarrier barrier_;
  RenderClock clock_;
  SnapshotPublisher publisher_{clock_};
  std::shared_ptr<PublishSignal> signal_;
  std::function<RowRenderer(const RenderJob&)> rowRendererFactory_;
  std::exception_ptr failure_;  // under the barrier's lock

  // Pass state.
  std::atomic<int> nextRow_{0};
  std::atomic<int> passRowsDone_{0};       // rows completed in the running pass (progress() reports them)
  std::atomic<uint64_t> resolveNanos_{0};  // worker time resolving rows for snapshots, ever
  std::atomic<bool> cancel_{false};
  std::atomic<bool> stopRequested_{false};
  std::atomic<bool> stopNow_{false};
  std::atomic<bool> abandonRows_{false};  // cancel_ or stopNow_: no new rows; rows rolled back leave theirs
  RowRollback rollbackMode_ = RowRollback::Auto;
  std::atomic<bool> rollBackRows_{true};  // in the running pass, decided at each boundary
  bool rowsAhead_ = false;                // some rows have a pass more than spp_ (after stopNow)
  std::vector<uint32_t> rowPasses_;       // row y: written by the worker that completes it
  std::atomic<bool> finished_{true};
  bool restingAtBoundary_ = false;        // under the barrier's lock: a worker waits paused at a boundary
  bool stopAll_ = false;                  // under the barrier's lock: the boundary ended the render
  std::atomic<uint32_t> spp_{0};          // completed passes; pass spp_ is the one being rendered
  std::atomic<double> passSeconds_{0.0};  // written before spp_ at each boundary (see progress())
  std::atomic<uint64_t> badSamples_{0};

  // The preview of an interactive start.
  std::atomic<int> nextPreviewRow_{0};
  Image preview_;
};

}  // namespace penumbra
