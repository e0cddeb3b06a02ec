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

using Clock = std::chrono::steady_clock;

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

void TevStreamer::follow(Engine& engine, std::string name) {
  std::lock_guard lk(mutex_);
  engine_ = &engine;
  engineName_ = std::move(name);
  cv_.notify_all();
}

void TevStreamer::offer(const std::string& name, const FilmSnapshot& snapshot) {
  std::lock_guard lk(mutex_);
  if (failed_ || stop_ || busy_ || pending_ || Clock::now() < nextDue_) return;
  if (snapshot.mean.empty() || snapshot.spp == 0) return;  // nothing yet, or the blocky preview
  if (snapshot.version == offeredVersion_ && name == offeredName_) return;
  offeredVersion_ = snapshot.version;
  offeredName_ = name;
  pending_ = TevFrame{name, snapshot.mean, Image()};
  ++submitted_;
  cv_.notify_all();
}

void TevStreamer::send(TevFrame frame) {
  std::unique_lock lk(mutex_);
  cv_.wait(lk, [&] { return failed_ || stop_ || !pending_; });
  if (failed_ || stop_) return;
  pending_ = std::move(frame);
  const uint64_t serial = ++submitted_;
  cv_.notify_all();
  cv_.wait(lk, [&] { return failed_ || completed_ >= serial; });
}

void TevStreamer::finish(std::optional<TevFrame> last) {
  {
    std::unique_lock lk(mutex_);
    engine_ = nullptr;  // the engine may go away once this returns
    if (last && !failed_ && !stop_) {
      cv_.wait(lk, [&] { return failed_ || !pending_; });
      if (!failed_) {
        pending_ = std::move(*last);
        ++submitted_;
      }
    }
    stop_ = true;
    cv_.notify_all();
  }
  if (thread_.joinable()) thread_.join();
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
  options_.warn("warning: display server " + server_.label() + ": " + why +
                (continuing ? "; continuing without it" : ""));
}

void TevStreamer::run() {
  std::string why;
  const bool connected = connection_.connect(server_, options_.connectSeconds, why);
  std::unique_lock lk(mutex_);
  busy_ = false;
  if (!connected) fail("cannot connect (" + why + ")", true);
  nextDue_ = Clock::now();
  const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
  while (!failed_) {
    if (pending_) {
      TevFrame frame = std::move(*pending_);
      pending_.reset();
      busy_ = true;
      lk.unlock();
      const auto began = Clock::now();
      const double cpu0 = threadCpuSeconds(), processCpu0 = processCpuSeconds();
      const bool ok = transmit(frame.name, frame.mean, frame.standardError, !frame.standardError.empty());
      lk.lock();
      busy_ = false;
      ++completed_;
      if (ok) scheduleNext(began, processCpu0, threadCpuSeconds() - cpu0, cores);
      cv_.notify_all();
      continue;
    }
    if (stop_) break;
    if (!engine_) {
      cv_.wait(lk);
      continue;
    }
    const auto now = Clock::now();
    const double cpuLeft = cpuDue_ - processCpuSeconds();
    if (now >= nextDue_ && cpuLeft <= 0) {
      pullFromEngine(lk);
      continue;
    }
    // Until the interval has passed, then in steps of what the CPU still owed takes at full speed.
    const double step = std::clamp(cpuLeft / std::max(engine_->threadCount(), 1), 0.01, 0.5);
    cv_.wait_until(lk, std::max(nextDue_, now + std::chrono::duration_cast<Clock::duration>(
                                                    std::chrono::duration<double>(step))));
  }
  if (failed_) return;
  lk.unlock();
  if (!connection_.finish(options_.closeSeconds, why)) {
    lk.lock();
    fail(why, false);
  }
}

// Asks the engine for a snapshot, waits for it (while still following and nothing else is to be
// sent) and sends it. Called and returns with `lock` held.
void TevStreamer::pullFromEngine(std::unique_lock<std::mutex>& lock) {
  Engine* engine = engine_;
  const std::string name = engineName_;
  const bool withError =
      options_.errorEvery > 0 && pulled_ % uint64_t(options_.errorEvery) == uint64_t(options_.errorEvery - 1);
  busy_ = true;
  lock.unlock();
  const auto began = Clock::now();
  const double cpu0 = threadCpuSeconds(), processCpu0 = processCpuSeconds();
  engine->takeSnapshot(snapshot_);  // drop an older publication: the update shows a pass still to come
  engine->requestNextPassSnapshot(withError);
  bool fresh = false;
  RenderProgress progress;
  lock.lock();
  while (!stop_ && engine_ == engine && !pending_) {
    lock.unlock();
    fresh = engine->takeSnapshot(snapshot_);
    progress = engine->progress();
    lock.lock();
    if (fresh || progress.finished) break;  // finished: the caller sends the last frame itself
    cv_.wait_for(lock, std::chrono::milliseconds(5));
  }
  bool ok = true;
  if (fresh && !progress.finished && snapshot_.spp > 0 && !snapshot_.mean.empty()) {
    ++pulled_;
    lock.unlock();
    ok = transmit(name, snapshot_.mean, snapshot_.standardError, true);
    lock.lock();
  }
  busy_ = false;
  const double own = threadCpuSeconds() - cpu0;
  if (ok) scheduleNext(began, processCpu0, own * (1 + kEngineWorkPerOwn), engine->threadCount());
  cv_.notify_all();
}

void TevStreamer::scheduleNext(Clock::time_point began, double beganProcessCpu, double workSeconds,
                               int threads) {
  const double interval =
      std::max(options_.minIntervalSeconds, workSeconds / (options_.costShare * std::max(threads, 1)));
  nextDue_ = began + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(interval));
  cpuDue_ = beganProcessCpu + workSeconds / options_.costShare;
}

// Runs on the sending thread, unlocked. On a failure, ends the stream with its warning.
bool TevStreamer::transmit(const std::string& name, const Image& mean, const Image& standardError,
                           bool errorLayer) {
  std::vector<TevLayer> layers = {{"", &mean}};
  if (errorLayer && !standardError.empty()) layers.push_back({"stderr.", &standardError});
  std::string why;
  bool ok = !connection_.peerClosed();
  if (!ok) why = "closed the connection";
  if (ok && (created_.name != name || created_.width != mean.width || created_.height != mean.height ||
             created_.errorLayer != errorLayer)) {
    std::vector<TevLayer> declared = {{"", &mean}};
    if (errorLayer) declared.push_back({"stderr.", &mean});
    encodeCreateImage({true, name, mean.width, mean.height, tevChannelNames(declared)}, packet_);
    ok = connection_.write(packet_, options_.stallSeconds, why);
    if (ok) created_ = {name, mean.width, mean.height, errorLayer};
  }
  for (const TileRect& tile : tevTiles(mean.width, mean.height)) {
    if (!ok) break;
    encodeUpdateImage(name, false, layers, tile, packet_);
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
