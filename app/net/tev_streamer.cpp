#include "app/net/tev_streamer.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <vector>

#include "app/net/tev_protocol.h"
#include "core/render/cpu_clock.h"

namespace penumbra::net {

namespace {

double threadCpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// The workers' share of an update (resolving the pass into a snapshot), per second of this thread's
// own work: at 768^2 the mean takes them ~3 ms against ~4 ms here, mean and standard error ~17 ms
// against ~6 ms; 2 over-counts a cycle of three updates of the mean and one with the error.
constexpr double kEngineWorkPerOwn = 2.0;

void warnOnStderr(const std::string& message) {
  // On a terminal, clear the render's progress bar line first (it redraws itself).
  std::fprintf(stderr, "%s%s\n", isatty(STDERR_FILENO) ? "\r\033[K" : "", message.c_str());
}

std::string secondsText(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g s", s);
  return buf;
}

}  // namespace

TevStreamer::TevStreamer(DisplayServer server, TevStreamOptions options)
    : server_(std::move(server)), options_(std::move(options)) {
  if (!options_.warn) options_.warn = warnOnStderr;
  nextDue_ = Clock::now();
  thread_ = std::thread([this] { run(); });
}

TevStreamer::~TevStreamer() {
  finish();
}

// Under mutex_.
bool TevStreamer::dueLocked(Clock::time_point now) const {
  return now >= nextDue_ && (options_.renderThreads <= 0 || processCpuSeconds() >= cpuDue_);
}

TevStreamer::Want TevStreamer::wanted() const {
  std::lock_guard lk(mutex_);
  Want w;
  w.frame = !failed_ && !stop_ && !busy_ && !pending_ && dueLocked(Clock::now());
  w.withError = options_.errorEvery > 0 &&
                offered_ % uint64_t(options_.errorEvery) == uint64_t(options_.errorEvery - 1);
  return w;
}

void TevStreamer::offer(const std::string& name, const FilmSnapshot& snapshot, bool errorLayer) {
  std::lock_guard lk(mutex_);
  if (failed_ || stop_ || busy_ || pending_ || !dueLocked(Clock::now())) return;
  if (snapshot.mean.empty() || snapshot.spp == 0) return;  // nothing yet, or the blocky preview
  if (snapshot.version == offeredVersion_ && name == offeredName_) return;
  offeredVersion_ = snapshot.version;
  offeredName_ = name;
  pending_ = TevFrame{name, snapshot.mean, errorLayer ? snapshot.standardError : Image(), errorLayer};
  pendingOffered_ = true;
  ++offered_;
  ++submitted_;
  cv_.notify_all();
}

void TevStreamer::startWaiting(const std::string& during) {
  waitingFor_ = during;
  connection_.setDeadline(Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                             std::chrono::duration<double>(options_.waitSeconds)));
}

// Under mutex_: an offered frame the sending thread has not begun is dropped (counted as handled).
void TevStreamer::dropPendingOffer() {
  if (!pending_ || !pendingOffered_) return;
  pending_.reset();
  ++completed_;
}

void TevStreamer::send(TevFrame frame) {
  std::unique_lock lk(mutex_);
  if (failed_ || stop_) return;
  startWaiting("an image was handed over");
  dropPendingOffer();                                  // this frame is newer
  cv_.wait(lk, [&] { return failed_ || !pending_; });  // the sending thread's every wait has the deadline
  if (!failed_) {
    pending_ = std::move(frame);
    pendingOffered_ = false;
    const uint64_t serial = ++submitted_;
    cv_.notify_all();
    cv_.wait(lk, [&] { return failed_ || completed_ >= serial; });
  }
  connection_.clearDeadline();
  waitingFor_.clear();
}

void TevStreamer::finish(std::optional<TevFrame> last) {
  if (!thread_.joinable()) return;
  {
    std::unique_lock lk(mutex_);
    if (!failed_) startWaiting("the render ended");
    dropPendingOffer();
    if (last && !failed_) {
      cv_.wait(lk, [&] { return failed_ || !pending_; });
      if (!failed_) {
        pending_ = std::move(*last);
        pendingOffered_ = false;
        ++submitted_;
      }
    }
    stop_ = true;
    cv_.notify_all();
  }
  thread_.join();
}

bool TevStreamer::failed() const {
  std::lock_guard lk(mutex_);
  return failed_;
}

uint64_t TevStreamer::updatesSent() const {
  std::lock_guard lk(mutex_);
  return updates_;
}

// Under mutex_. Ends the stream with its one warning.
void TevStreamer::fail(const std::string& why, bool continuing) {
  failed_ = true;
  pending_.reset();
  completed_ = submitted_;
  cv_.notify_all();
  std::string message = why;
  if (!waitingFor_.empty() && connection_.pastDeadline()) {
    message = "too slow: still busy " + secondsText(options_.waitSeconds) + " after " + waitingFor_ +
              "; dropped it";
    continuing = false;
  }
  options_.warn("warning: display server " + server_.label() + ": " + message +
                (continuing ? "; continuing without it" : ""));
}

void TevStreamer::run() {
  std::string what;
  try {
    stream();
    return;
  } catch (const std::exception& e) {
    what = e.what();
  } catch (...) {
    what = "an unknown exception";
  }
  std::lock_guard lk(mutex_);
  busy_ = false;
  if (!failed_) fail("cannot send (" + what + ")", true);
}

void TevStreamer::stream() {
  std::string why;
  const bool connected = connection_.connect(server_, options_.connectSeconds, why);
  std::unique_lock lk(mutex_);
  busy_ = false;
  if (!connected) fail("cannot connect (" + why + ")", true);
  nextDue_ = Clock::now();
  while (!failed_) {
    if (pending_) {
      TevFrame frame = std::move(*pending_);
      const bool offered = pendingOffered_;
      pending_.reset();
      busy_ = true;
      lk.unlock();
      const auto began = Clock::now();
      const double cpu0 = threadCpuSeconds(), processCpu0 = processCpuSeconds();
      const bool ok = transmit(frame);
      lk.lock();
      busy_ = false;
      ++completed_;
      if (ok && offered) {
        const double own = threadCpuSeconds() - cpu0;
        scheduleNext(began, processCpu0, options_.renderThreads > 0 ? own * (1 + kEngineWorkPerOwn) : own);
      }
      cv_.notify_all();
      continue;
    }
    if (stop_) break;
    cv_.wait(lk);
  }
  if (failed_) return;
  lk.unlock();
  if (!connection_.finish(options_.closeSeconds, why)) {
    lk.lock();
    fail(why, false);
  }
}

void TevStreamer::scheduleNext(Clock::time_point began, double beganProcessCpu, double workSeconds) {
  const int threads = options_.renderThreads > 0 ? options_.renderThreads
                                                 : int(std::max(1u, std::thread::hardware_concurrency()));
  const double interval = std::max(options_.minIntervalSeconds, workSeconds / (options_.costShare * threads));
  nextDue_ = began + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(interval));
  cpuDue_ = beganProcessCpu + workSeconds / options_.costShare;
}

// Runs on the sending thread, unlocked. On a failure, ends the stream with its warning.
bool TevStreamer::transmit(const TevFrame& frame) {
  const Image& mean = frame.mean;
  const bool errorLayer = frame.errorLayer || !frame.standardError.empty();
  std::vector<TevLayer> layers = {{"", &mean}};
  if (!frame.standardError.empty()) layers.push_back({"stderr.", &frame.standardError});
  std::string why;
  bool ok = !connection_.peerClosed();
  if (!ok) why = "closed the connection";
  if (ok && (created_.name != frame.name || created_.width != mean.width || created_.height != mean.height ||
             created_.errorLayer != errorLayer)) {
    std::vector<TevLayer> declared = {{"", &mean}};
    if (errorLayer) declared.push_back({"stderr.", &mean});
    encodeCreateImage({true, frame.name, mean.width, mean.height, tevChannelNames(declared)}, packet_);
    ok = connection_.write(packet_, options_.stallSeconds, why);
    if (ok) created_ = {frame.name, mean.width, mean.height, errorLayer};
  }
  for (const TileRect& tile : tevTiles(mean.width, mean.height)) {
    if (!ok) break;
    encodeUpdateImage(frame.name, false, layers, tile, packet_);
    ok = connection_.write(packet_, options_.stallSeconds, why);
  }
  std::lock_guard lk(mutex_);
  if (!ok) {
    created_ = {};
    fail(why, true);
    return false;
  }
  ++updates_;
  return true;
}

}  // namespace penumbra::net
