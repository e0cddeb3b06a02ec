// The TCP side of talking to tev: the HOST[:PORT] of --display-server, resolved once up front, and a
// connection whose every operation has a timeout (a tev that stops reading, or never accepts, can
// hold up the sending thread for at most that long, never forever), and which another thread can give
// a deadline that ends whatever it is doing (a stream that may take only so long after a render).
#pragma once

#include <sys/socket.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace penumbra::net {

struct DisplayServer {
  std::string host;
  uint16_t port = 0;
  struct Address {
    sockaddr_storage storage{};
    socklen_t length = 0;
    int family = 0;
  };
  std::vector<Address> addresses;  // what the host resolved to, tried in order
  std::string label() const;       // "host:port" as the user wrote it (IPv6 in brackets)
};

// Parses HOST, HOST:PORT, [IPV6] or [IPV6]:PORT (default port: tev's 14158) and resolves the host.
// Throws penumbra::Error naming the option and what was expected: a malformed value, a port outside
// 1..65535, a name that is not a host name, or one that does not resolve.
DisplayServer resolveDisplayServer(const std::string& spec);

class TevConnection {
 public:
  TevConnection() = default;
  ~TevConnection();
  TevConnection(const TevConnection&) = delete;
  TevConnection& operator=(const TevConnection&) = delete;

  using Clock = std::chrono::steady_clock;

  // From any thread: connect, write and finish give up at `deadline` (within about 20 ms of it), with
  // `why` saying so, and close the socket. clearDeadline() lifts it.
  void setDeadline(Clock::time_point deadline);
  void clearDeadline();
  bool pastDeadline() const;

  // Connects to the first address that accepts within timeoutSeconds. False with `why` otherwise.
  bool connect(const DisplayServer& server, double timeoutSeconds, std::string& why);
  // Writes all of `bytes`. False with `why` when the peer has gone, on a socket error, or when the peer
  // took none of the bytes for stallSeconds (it stopped reading).
  bool write(std::span<const uint8_t> bytes, double stallSeconds, std::string& why);
  // tev never sends anything: a readable socket means it closed the connection (or reset it).
  bool peerClosed();
  // Ends the stream: no more writes, then waits until the peer has read everything and closed its end
  // (what tev does on end of stream), for at most timeoutSeconds after it last took bytes. False with
  // `why` when it did not (the last bytes may not have arrived). Closes the socket either way.
  bool finish(double timeoutSeconds, std::string& why);
  bool connected() const { return fd_ >= 0; }

 private:
  void close();
  // Waits for `events` on `fd` for at most `seconds`, in slices that watch the deadline: > 0 when
  // they came, 0 on timeout, -1 past the deadline or on a poll error (errno set; 0 for the deadline).
  int waitFor(int fd, short events, double seconds);
  int fd_ = -1;
  std::atomic<Clock::rep> deadline_{Clock::time_point::max().time_since_epoch().count()};
};

}  // namespace penumbra::net
