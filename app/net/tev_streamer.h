// Streams a progressive render to tev from a thread of its own: connects, creates the image, then
// sends it as tiles (tev_protocol.h) whenever an update is due. Nothing here blocks a render thread:
// the engine is only asked for snapshots (Engine::requestNextPassSnapshot / takeSnapshot), and every
// socket operation has a deadline. The first failure (tev not running, refusing, gone, not reading) prints
// one warning and ends the stream; whoever renders carries on.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "app/net/tev_client.h"
#include "core/image/image.h"
#include "core/render/engine.h"

namespace penumbra::net {

// One image as tev shows it: channels R, G, B, and, when standardError is not empty, the per-pixel
// standard error of the mean as the layer "stderr" (channels stderr.R, stderr.G, stderr.B).
struct TevFrame {
  std::string name;
  Image mean;
  Image standardError;
};

struct TevStreamOptions {
  // Pacing: after each update the next is due once the work it cost is costShare of the render
  // threads' time since it began, and never sooner than minIntervalSeconds. Following an engine, that
  // time is also counted in process CPU time, so a render that gets less than its cores (a busy
  // machine) is updated less often. The work: this thread's CPU time (copying, encoding, sending) and,
  // following an engine, the workers' resolve of the snapshot (Engine::requestNextPassSnapshot: inside
  // the pass, no worker waits), counted as twice this thread's (tev_streamer.cpp).
  double minIntervalSeconds = 0.25;
  double costShare = 0.01;
  // Following an engine, every errorEvery-th update also carries the standard error (resolving it
  // costs the workers about five times what the mean does); the last frame always does.
  int errorEvery = 4;
  double connectSeconds = 3;  // to connect
  double stallSeconds = 5;    // longest wait for tev to take bytes mid-stream
  double closeSeconds = 2;    // longest wait, at the end, for tev to confirm it read everything
  // Receives the one warning (default: a line on stderr).
  std::function<void(const std::string&)> warn;
};

class TevStreamer {
 public:
  // Starts the sending thread, which connects at once. `server` comes from resolveDisplayServer.
  explicit TevStreamer(DisplayServer server, TevStreamOptions options = {});
  ~TevStreamer();  // finish() without a last frame
  TevStreamer(const TevStreamer&) = delete;
  TevStreamer& operator=(const TevStreamer&) = delete;

  // From now on, whenever an update is due, asks `engine` for a snapshot (the standard error with every
  // errorEvery-th) and sends it as `name`, with the stderr layer. The streamer becomes the engine's only
  // snapshot reader (it uses takeSnapshot); call finish() before the engine is destroyed.
  void follow(Engine& engine, std::string name);
  // A snapshot someone else reads (the viewer's), as R, G, B. Copied and sent only when an update is
  // due and it is newer than the last one taken, so it is cheap to call on every poll.
  void offer(const std::string& name, const FilmSnapshot& snapshot);
  // Sends `frame` (after what is being sent) and returns once it is sent or the stream has failed.
  void send(TevFrame frame);
  // Stops following the engine, sends `last` if given, ends the stream and joins the thread. Takes at
  // most about connectSeconds + stallSeconds + closeSeconds when tev misbehaves.
  void finish(std::optional<TevFrame> last = std::nullopt);

  bool failed() const;
  uint64_t updatesSent() const;  // whole-image updates sent so far

 private:
  void run();
  void pullFromEngine(std::unique_lock<std::mutex>& lock);
  // Sends one image as `name`; creates it in tev first when its name, size or channels changed.
  // errorLayer: the image has the stderr layer (its tiles are sent when standardError is not empty).
  bool transmit(const std::string& name, const Image& mean, const Image& standardError, bool errorLayer);
  void fail(const std::string& why, bool continuing);
  // Under mutex_: when the next update is due, from when this one began (wall clock and process CPU
  // time) and the work it cost.
  void scheduleNext(std::chrono::steady_clock::time_point began, double beganProcessCpu, double workSeconds,
                    int threads);

  DisplayServer server_;
  TevStreamOptions options_;
  TevConnection connection_;

  mutable std::mutex mutex_;
  std::condition_variable cv_;
  bool stop_ = false, failed_ = false, busy_ = true;  // busy_: connecting or sending
  Engine* engine_ = nullptr;
  std::string engineName_;
  std::optional<TevFrame> pending_;
  uint64_t submitted_ = 0, completed_ = 0;  // frames given to send() / finish(), and handled
  uint64_t offeredVersion_ = ~0ull;
  std::string offeredName_;
  std::chrono::steady_clock::time_point nextDue_;  // no update before this
  double cpuDue_ = 0;  // following an engine, nor before the process has used this much CPU time
  uint64_t updates_ = 0;

  // Touched by the sending thread only.
  FilmSnapshot snapshot_;
  std::vector<uint8_t> packet_;
  uint64_t pulled_ = 0;  // snapshots taken from the engine
  struct Created {
    std::string name;
    int width = 0, height = 0;
    bool errorLayer = false;
  } created_;

  std::thread thread_;
};

}  // namespace penumbra::net
