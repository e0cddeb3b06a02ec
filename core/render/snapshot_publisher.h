// Publishing the film's estimate to readers (a viewer) at pass boundaries: snapshot requests, the
// double-buffered snapshot, the choice between resolving a pass row by row and resolving the whole
// film at its boundary, and the probe pixel each snapshot carries.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>

#include "core/image/image.h"
#include "core/render/film.h"
#include "core/render/render_clock.h"

namespace penumbra {

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

// Pixel (x, y)'s statistics from a film at rest (a pass boundary) after `spp` passes; out.x < 0 when
// the pixel is outside the film or x < 0.
void filmProbe(const Film& film, uint32_t spp, int x, int y, FilmSnapshot::Probe& out);

class SnapshotPublisher {
 public:
  // Snapshots are stamped with this clock's readings.
  explicit SnapshotPublisher(const RenderClock& clock) : clock_(clock) {}

  // Any thread.
  void request(bool withStandardError);
  // The pass after the running one is resolved row by row and published at its end; no later pass is
  // (a reader that wants a snapshot now and then without holding up the workers).
  void requestNextPass(bool withStandardError);
  void setProbePixel(int x, int y);
  bool latest(FilmSnapshot& out) const;
  bool take(FilmSnapshot& out);

  // While no worker runs: a new accumulation shows an empty snapshot (spp 0, a new version) at once.
  void restart();
  // While no worker runs: whether the coming pass resolves its rows (an interactive start, or a
  // render of one pass).
  void resolveNextPassRows(bool resolve, const Film& film) { prepareResolve(resolve, false, film); }

  // Workers during a pass: where a finished row's mean and standard error go (nullptr: not resolved
  // row by row this pass).
  Image* rowMeanTarget() { return resolveMean_ ? &pendingMean_ : nullptr; }
  Image* rowErrorTarget() { return resolveError_ ? &pendingError_ : nullptr; }

  // The last worker at a boundary, after pass `spp` (`last`: the render stops here, which is always
  // published). Publishes if asked to, then chooses how the next pass is resolved: row by row when
  // asked to, and when it is known to be the render's last (`nextIsLast`), so the final image is
  // resolved by all workers as they go instead of by one at the end. True if published.
  bool atPassBoundary(const Film& film, uint32_t spp, bool last, bool nextIsLast = false);
  // Publishes a preview image (spp 0).
  void publishPreview(Image&& image);
  // The film at rest after `spp` passes: publishes it unless that pass, with the requested standard
  // error, already is. True if published.
  bool publishIfStale(const Film& film, uint32_t spp);

 private:
  void publishWhole(const Film& film, uint32_t spp);
  void publishResolved(const Film& film, uint32_t spp);
  void stamp(const Film& film, uint32_t spp, bool withError);
  void prepareResolve(bool mean, bool error, const Film& film);

  const RenderClock& clock_;
  std::atomic<uint64_t> probePixel_{~0ull};  // (x << 32) | y, ~0: none
  std::atomic<bool> requested_{false};
  std::atomic<bool> wantsError_{false};
  std::atomic<bool> nextPassRequested_{false};
  std::atomic<bool> nextPassWantsError_{false};
  std::atomic<uint64_t> requests_{0}, errorRequests_{0};
  uint64_t requestsSeen_[2] = {0, 0}, errorRequestsSeen_[2] = {0, 0};  // at the last two boundaries
  bool resolveMean_ = false, resolveError_ = false;  // the current pass resolves its rows into:
  Image pendingMean_, pendingError_;
  mutable std::mutex mutex_;
  FilmSnapshot snapshot_;
  bool publishedError_ = false;  // snapshot_ was published with its standard error (mutex_)
};

}  // namespace penumbra
