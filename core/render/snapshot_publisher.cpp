#include "core/render/snapshot_publisher.h"

#include <utility>

namespace penumbra {

namespace {

// A pixel as one atomic word: (x << 32) | y; ~0 for none.
uint64_t packPixel(int x, int y) {
  return x < 0 || y < 0 ? ~0ull : (uint64_t(uint32_t(x)) << 32) | uint32_t(y);
}

}  // namespace

void filmProbe(const Film& film, uint32_t spp, int x, int y, FilmSnapshot::Probe& out) {
  out = FilmSnapshot::Probe();
  if (x < 0 || y < 0 || x >= film.width() || y >= film.height()) return;
  out.x = x, out.y = y;
  film.pixelStatistics(spp, x, y, out.mean, out.standardError);
}

void SnapshotPublisher::request(bool withStandardError) {
  if (withStandardError) {
    wantsError_ = true;
    ++errorRequests_;
  }
  ++requests_;
  requested_ = true;
}

void SnapshotPublisher::setProbePixel(int x, int y) {
  probePixel_ = packPixel(x, y);
}

bool SnapshotPublisher::latest(FilmSnapshot& out) const {
  std::lock_guard lk(mutex_);
  if (snapshot_.version == out.version) return false;
  out = snapshot_;
  return true;
}

bool SnapshotPublisher::take(FilmSnapshot& out) {
  std::lock_guard lk(mutex_);
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

void SnapshotPublisher::requestNextPass(bool withStandardError) {
  if (withStandardError) nextPassWantsError_ = true;
  nextPassRequested_ = true;
}

void SnapshotPublisher::restart() {
  nextPassRequested_ = false;
  nextPassWantsError_ = false;
  std::lock_guard lk(mutex_);
  snapshot_.spp = 0;
  snapshot_.seconds = 0;
  snapshot_.cpuSeconds = 0;
  ++snapshot_.version;  // viewers see the restart at once
  snapshot_.mean = Image();
  snapshot_.standardError = Image();
}

void SnapshotPublisher::prepareResolve(bool mean, bool error, const Film& film) {
  resolveMean_ = mean;
  resolveError_ = mean && error;
  const int w = film.width(), h = film.height();
  if (resolveMean_ && (pendingMean_.width != w || pendingMean_.height != h)) pendingMean_ = Image(w, h);
  if (resolveError_ && (pendingError_.width != w || pendingError_.height != h)) pendingError_ = Image(w, h);
}

bool SnapshotPublisher::atPassBoundary(const Film& film, uint32_t spp, bool last, bool nextIsLast) {
  const bool requested = requested_.exchange(false);
  const bool published = resolveMean_ || requested || last;
  if (resolveMean_)
    publishResolved(film, spp);
  else if (requested || last)
    publishWhole(film, spp);
  // Resolve the next pass row by row while requests keep coming (one since either of the last two
  // boundaries): a viewer asks again right after it fetched a snapshot, i.e. early in the next pass.
  const uint64_t r = requests_, e = errorRequests_;
  bool mean = !last && (r != requestsSeen_[0] || requestsSeen_[0] != requestsSeen_[1]);
  bool error = e != errorRequestsSeen_[0] || errorRequestsSeen_[0] != errorRequestsSeen_[1];
  requestsSeen_[1] = requestsSeen_[0], requestsSeen_[0] = r;
  errorRequestsSeen_[1] = errorRequestsSeen_[0], errorRequestsSeen_[0] = e;
  if (!last && nextPassRequested_.exchange(false)) {
    mean = true;
    error = nextPassWantsError_.exchange(false) || error;
  }
  if (nextIsLast) {
    mean = true;
    error = error || wantsError_;
  }
  prepareResolve(mean, error, film);
  return published;
}

void SnapshotPublisher::publishPreview(Image&& image) {
  std::lock_guard lk(mutex_);
  snapshot_.mean = std::move(image);
  snapshot_.standardError = Image();
  snapshot_.probe = FilmSnapshot::Probe();  // no pass yet
  snapshot_.spp = 0;
  publishedError_ = false;
  snapshot_.seconds = clock_.elapsed();
  snapshot_.cpuSeconds = clock_.cpuSeconds();
  ++snapshot_.version;
}

bool SnapshotPublisher::publishIfStale(const Film& film, uint32_t spp) {
  {
    // By what was published, not by snapshot_'s images: take() swaps those with old buffers.
    std::lock_guard lk(mutex_);
    const bool errorMissing = wantsError_ && !publishedError_ && spp >= 2;
    if (snapshot_.spp == spp && !errorMissing) return false;
  }
  publishWhole(film, spp);
  return true;
}

// Resolves the whole film at the boundary (the other workers wait meanwhile).
void SnapshotPublisher::publishWhole(const Film& film, uint32_t spp) {
  const bool withError = wantsError_.exchange(false);
  Image mean = film.mean(spp);
  Image err;
  if (withError) err = film.standardError(spp);
  std::lock_guard lk(mutex_);
  snapshot_.mean = std::move(mean);
  snapshot_.standardError = std::move(err);
  stamp(film, spp, withError);
}

// The pass that just ended was resolved row by row into pendingMean_ (and pendingError_): publish it
// by swapping buffers (the old snapshot's become the next pass's pending ones; readers copy).
void SnapshotPublisher::publishResolved(const Film& film, uint32_t spp) {
  std::lock_guard lk(mutex_);
  std::swap(snapshot_.mean, pendingMean_);
  if (resolveError_) {
    std::swap(snapshot_.standardError, pendingError_);
    wantsError_ = false;
  } else {
    snapshot_.standardError = Image();
  }
  stamp(film, spp, resolveError_);
}

// The rest of a publication, under mutex_, once the images are in place.
void SnapshotPublisher::stamp(const Film& film, uint32_t spp, bool withError) {
  snapshot_.spp = spp;
  publishedError_ = withError;
  const uint64_t p = probePixel_;
  if (p == ~0ull || spp == 0)
    snapshot_.probe = FilmSnapshot::Probe();
  else
    filmProbe(film, spp, int(p >> 32), int(uint32_t(p)), snapshot_.probe);
  snapshot_.seconds = clock_.elapsed();
  snapshot_.cpuSeconds = clock_.cpuSeconds();
  ++snapshot_.version;
}

}  // namespace penumbra
