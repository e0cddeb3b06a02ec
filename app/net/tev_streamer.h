// Streams images to tev from a thread of its own: connects, creates each image, then sends it as tiles
// (tev_protocol.h). The stream is best effort and never holds up whoever renders: frames are offered
// (copied, then sent on this thread; an offer while a frame is still being sent is dropped), every
// socket operation has a timeout, and whoever waits for the stream (send, finish) waits at most
// waitSeconds, after which the stream is dropped. The first failure (tev not running, refusing, gone,
// not reading, too slow at the end) prints one warning and ends the stream; the caller carries on.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "app/net/tev_client.h"
#include "core/image/image.h"
#include "core/render/snapshot_publisher.h"

namespace penumbra::net {

// One image as tev shows it: channels R, G, B and, with errorLayer or a standardError, the layer
// "stderr" (channels stderr.R, stderr.G, stderr.B) holding the per-pixel standard error of the mean.
// errorLayer declares the layer even in a frame that does not carry it (tev keeps the last one sent),
// so an image whose frames carry it now and then is created in tev once.
struct TevFrame {
  std::string name;
  Image mean;
  Image standardError;
  bool errorLayer = false;
};

struct TevStreamOptions {
  // Pacing of offered frames: after each update the next is due once the work it cost is costShare of
  // the render threads' time since it began, and never sooner than minIntervalSeconds.
  double minIntervalSeconds = 0.25;
  double costShare = 0.01;
  // > 0: the offered frames are snapshots the renderer resolved because the stream wanted them
  // (wanted()), on this many threads. Their resolve is then counted as twice this thread's own work
  // (tev_streamer.cpp), and the pacing also waits for that share of process CPU time, so a render that
  // gets less than its cores (a busy machine) is updated less often.
  int renderThreads = 0;
  // Every errorEvery-th wanted frame asks for the standard error too (resolving it costs the workers
  // about five times what the mean does).
  int errorEvery = 4;
  double connectSeconds = 3;  // to connect
  double stallSeconds = 5;    // longest wait for tev to take bytes mid-stream
  double closeSeconds = 2;    // longest wait, at the end, for tev to confirm it read everything
  // Longest send() and finish() wait for the stream: whatever it is still doing then (connecting,
  // sending, waiting for tev to read) is abandoned and the stream dropped with its warning.
  double waitSeconds = 1;
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

  // Whether offer() would take a frame now (connected, idle, and an update is due), and whether that
  // frame should carry the standard error. For a render loop that asks its engine for a snapshot
  // only when the stream wants one.
  struct Want {
    bool frame = false;
    bool withError = false;
  };
  Want wanted() const;
  // A snapshot (its mean, and its standard error when errorLayer and it has one): copied and sent when
  // an update is due and the stream is idle, dropped otherwise; a snapshot already offered under
  // `name` is skipped. Cheap when dropped, so it can be called on every poll.
  void offer(const std::string& name, const FilmSnapshot& snapshot, bool errorLayer = false);
  // Sends `frame` after what is being sent; returns once it is sent, the stream has failed, or
  // waitSeconds have passed (then the stream is dropped).
  void send(TevFrame frame);
  // Sends `last` if given, ends the stream and joins the thread, all within waitSeconds (and a few
  // tens of ms); after that the stream is dropped with its warning.
  void finish(std::optional<TevFrame> last = std::nullopt);

  bool failed() const;
  uint64_t updatesSent() const;  // whole-image updates sent so far

 private:
  using Clock = std::chrono::steady_clock;

  // The sending thread: stream(), and any exception it throws (an allocation failing while a frame
  // is encoded, say) ends the stream with its one warning, as a socket fault does.
  void run();
  void stream();
  // Sends one frame; creates the image in tev first when its name, size or layers changed.
  bool transmit(const TevFrame& frame);
  void fail(const std::string& why, bool continuing);
  // Under mutex_: the connection gives up waitSeconds from now; a failure after it says `during`.
  void startWaiting(const std::string& during);
  void dropPendingOffer();                      // under mutex_
  bool dueLocked(Clock::time_point now) const;  // under mutex_: an offered frame may be taken
  // Under mutex_: when the next update is due, from when this one began (wall clock and process CPU
  // time) and the work it cost.
  void scheduleNext(Clock::time_point began, double beganProcessCpu, double workSeconds);

  DisplayServer server_;
  TevStreamOptions options_;
  TevConnection connection_;

  mutable std::mutex mutex_;
  std::condition_variable cv_;
  bool stop_ = false, failed_ = false, busy_ = true;  // busy_: connecting or sending
  std::optional<TevFrame> pending_;
  bool pendingOffered_ = false;             // pending_ came from offer()
  uint64_t submitted_ = 0, completed_ = 0;  // frames taken (offer, send, finish), and handled or dropped
  uint64_t offered_ = 0;                    // frames offer() took
  uint64_t offeredVersion_ = ~0ull;
  std::string offeredName_;
  Clock::time_point nextDue_;  // no offered frame before this
  double cpuDue_ = 0;          // with renderThreads, nor before the process has used this much CPU time
  std::string waitingFor_;     // what a caller is waiting for, while one is (startWaiting)
  uint64_t updates_ = 0;

  // Touched by the sending thread only.
  std::vector<uint8_t> packet_;
  struct Created {
    std::string name;
    int width = 0, height = 0;
    bool errorLayer = false;
  } created_;

  std::thread thread_;
};

}  // namespace penumbra::net
