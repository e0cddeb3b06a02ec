// A stand-in for the tev image viewer inside the test process: a TCP listener on an ephemeral port of
// 127.0.0.1 (nothing else), served by a thread of its own. It decodes every packet with
// app/net/tev_protocol.h, rebuilds each image from its tiles, and records what a test checks: names,
// channel lists, every tile, and anything malformed. Modes reproduce the viewers a client must survive
// (see Mode). Every wait is bounded; the thread stops when the object is destroyed.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <exception>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "app/net/tev_client.h"
#include "app/net/tev_protocol.h"

namespace penumbra::test {

class FakeTev {
 public:
  enum class Mode {
    Serve,                  // reads and decodes everything, as tev does
    CloseAfterFirstPacket,  // closes the connection after the first whole packet
    NeverAccept,            // listens, never accepts: the kernel completes handshakes into the backlog
    BacklogFull,            // listens with a full backlog (filled by the fake itself): SYNs are dropped
    NeverRead,              // accepts, never reads
    CloseAtOnce,            // accepts and closes at once
    Reset,                  // accepts and resets the connection (RST) at once
    Garbage,                // sends bytes that are not tev's protocol all along, and reads as Serve does
    SlowReader,             // reads 64 KB every 100 ms (small receive buffer), decoding as Serve does
  };

  struct ReceivedImage {
    int width = 0, height = 0;
    std::vector<std::string> channels;
    std::vector<std::vector<float>> planes;  // per channel, row-major; NaN where nothing arrived
    int creates = 0;
    // Every tile received, with the channels it carried.
    struct Tile {
      net::TileRect rect;
      std::vector<std::string> channels;
    };
    std::vector<Tile> tiles;

    int channel(const std::string& name) const {
      for (size_t i = 0; i < channels.size(); ++i)
        if (channels[i] == name) return int(i);
      return -1;
    }
    float at(const std::string& name, int x, int y) const {
      return planes[size_t(channel(name))][size_t(y) * size_t(width) + size_t(x)];
    }

    // How the tiles that carried `channel` cover the image: "" when they are whole updates, i.e. the
    // distinct tiles partition the image (every pixel in exactly one) and each was sent equally often
    // (that count goes to *updates); otherwise what is wrong.
    std::string coverage(const std::string& name, int* updates = nullptr) const {
      std::vector<net::TileRect> distinct;
      std::vector<int> sent;
      for (const Tile& t : tiles) {
        if (std::find(t.channels.begin(), t.channels.end(), name) == t.channels.end()) continue;
        auto it = std::find(distinct.begin(), distinct.end(), t.rect);
        if (it == distinct.end()) {
          distinct.push_back(t.rect);
          sent.push_back(1);
        } else {
          ++sent[size_t(it - distinct.begin())];
        }
      }
      if (distinct.empty()) return "no tile carried " + name;
      std::vector<int> covered(size_t(width) * size_t(height), 0);
      for (const net::TileRect& r : distinct)
        for (int y = r.y; y < r.y + r.height; ++y)
          for (int x = r.x; x < r.x + r.width; ++x) ++covered[size_t(y) * size_t(width) + size_t(x)];
      for (size_t i = 0; i < covered.size(); ++i)
        if (covered[i] != 1)
          return "pixel " + std::to_string(i % size_t(width)) + "," + std::to_string(i / size_t(width)) +
                 " is in " + std::to_string(covered[i]) + " distinct tiles of " + name;
      for (int n : sent)
        if (n != sent[0])
          return "tiles of " + name + " sent unequally often (" + std::to_string(n) + " vs " +
                 std::to_string(sent[0]) + ")";
      if (updates) *updates = sent[0];
      return "";
    }
  };

  explicit FakeTev(Mode mode = Mode::Serve) : mode_(mode) {
    listener_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = 0;  // ephemeral
    socklen_t len = sizeof a;
    if (mode == Mode::SlowReader && listener_ >= 0) {  // accepted sockets inherit it
      const int bytes = kSlowChunk;
      ::setsockopt(listener_, SOL_SOCKET, SO_RCVBUF, &bytes, sizeof bytes);
    }
    if (listener_ < 0 || ::bind(listener_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
        ::listen(listener_, mode == Mode::BacklogFull ? 0 : 4) != 0 ||
        ::getsockname(listener_, reinterpret_cast<sockaddr*>(&a), &len) != 0) {
      problem("cannot listen on 127.0.0.1");
      return;
    }
    port_ = ntohs(a.sin_port);
    if (mode == Mode::BacklogFull) fillBacklog(a);
    thread_ = std::thread([this] { serve(); });
  }
  ~FakeTev() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
    if (listener_ >= 0) ::close(listener_);
    for (int fd : fillers_) ::close(fd);
  }
  FakeTev(const FakeTev&) = delete;
  FakeTev& operator=(const FakeTev&) = delete;

  int port() const { return port_; }
  std::string address() const { return "127.0.0.1:" + std::to_string(port_); }

  // Waits until `connections` clients have ended their streams (end of stream read, or the fake closed
  // them), at most `seconds`. True when they did.
  bool waitForStreamsEnded(int connections, double seconds) {
    std::unique_lock lk(mutex_);
    return cv_.wait_for(lk, std::chrono::duration<double>(seconds), [&] { return ended_ >= connections; });
  }

  // Snapshots of what arrived (copied under the lock).
  std::map<std::string, ReceivedImage> images() const {
    std::lock_guard lk(mutex_);
    return images_;
  }
  std::vector<std::string> problems() const {
    std::lock_guard lk(mutex_);
    return problems_;
  }
  int packets() const {
    std::lock_guard lk(mutex_);
    return packets_;
  }
  int connections() const {
    std::lock_guard lk(mutex_);
    return accepted_;
  }

 private:
  static constexpr double kMaxLifeSeconds = 300;  // the thread gives up on its own after this
  static constexpr int kSlowChunk = 1 << 16;      // SlowReader: bytes per read, and the receive buffer

  // Connections of the fake's own that nobody accepts: with a backlog of 0 the first one fills it (the
  // kernel queues backlog + 1), the next waits; later SYNs are dropped and a client's connect hangs.
  void fillBacklog(const sockaddr_in& at) {
    for (int i = 0; i < 2; ++i) {
      const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
      if (fd < 0) continue;
      ::connect(fd, reinterpret_cast<const sockaddr*>(&at), sizeof at);  // EINPROGRESS: completes, or not
      fillers_.push_back(fd);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));  // the first handshake completes
  }

  void problem(const std::string& p) {
    std::lock_guard lk(mutex_);
    problems_.push_back(p);
  }

  void serve() {
    const auto began = std::chrono::steady_clock::now();
    auto alive = [&] {
      return !stop_ && std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count() <
                           kMaxLifeSeconds;
    };
    while (alive()) {
      if (mode_ == Mode::NeverAccept || mode_ == Mode::BacklogFull) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        continue;
      }
      pollfd p{listener_, POLLIN, 0};
      if (::poll(&p, 1, 20) <= 0) continue;
      const int fd = ::accept4(listener_, nullptr, nullptr, SOCK_CLOEXEC);
      if (fd < 0) continue;
      {
        std::lock_guard lk(mutex_);
        ++accepted_;
      }
      if (mode_ == Mode::Reset) {
        const linger abort{1, 0};  // close() sends RST instead of FIN
        ::setsockopt(fd, SOL_SOCKET, SO_LINGER, &abort, sizeof abort);
      } else if (mode_ == Mode::NeverRead) {
        while (alive()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
      } else if (mode_ != Mode::CloseAtOnce) {
        readConnection(fd, alive);
      }
      ::close(fd);
      {
        std::lock_guard lk(mutex_);
        ++ended_;
      }
      cv_.notify_all();
    }
  }

  // Reads packets until end of stream (or, in CloseAfterFirstPacket mode, the first whole packet).
  template <class Alive>
  void readConnection(int fd, Alive alive) {
    std::vector<uint8_t> buffer;
    uint8_t chunk[kSlowChunk];
    static const char garbage[] = "HTTP/1.1 400 Bad Request\r\n\r\n\x00\xff\x13\x37 not tev\n";
    while (alive()) {
      if (mode_ == Mode::Garbage)
        ::send(fd, garbage, sizeof garbage - 1, MSG_DONTWAIT | MSG_NOSIGNAL);  // dropped when full
      if (mode_ == Mode::SlowReader) std::this_thread::sleep_for(std::chrono::milliseconds(100));
      pollfd p{fd, POLLIN, 0};
      if (::poll(&p, 1, 20) <= 0) continue;
      const ssize_t n = ::recv(fd, chunk, sizeof chunk, 0);
      if (n == 0) break;  // the client ended its stream
      if (n < 0) {
        problem(std::string("recv failed: ") + std::strerror(errno));
        break;
      }
      buffer.insert(buffer.end(), chunk, chunk + n);
      size_t used = 0;
      try {
        for (size_t len; (len = net::tevPacketLength({buffer.data() + used, buffer.size() - used})) > 0 &&
                         buffer.size() - used >= len;
             used += len) {
          apply(net::decodeTevPacket({buffer.data() + used, len}));
          if (mode_ == Mode::CloseAfterFirstPacket) return;
        }
      } catch (const std::exception& e) {
        problem(e.what());
        return;
      }
      buffer.erase(buffer.begin(), buffer.begin() + std::ptrdiff_t(used));
    }
    if (!buffer.empty()) problem(std::to_string(buffer.size()) + " bytes of an incomplete packet at the end");
  }

  void apply(const net::TevPacket& packet) {
    std::lock_guard lk(mutex_);
    ++packets_;
    if (const auto* c = std::get_if<net::TevCreateImage>(&packet)) {
      ReceivedImage& img = images_[c->name];
      const int creates = img.creates;
      img = ReceivedImage();
      img.creates = creates + 1;
      img.width = c->width, img.height = c->height;
      img.channels = c->channels;
      img.planes.assign(c->channels.size(), std::vector<float>(size_t(c->width) * size_t(c->height), NAN));
      return;
    }
    const auto& u = std::get<net::TevUpdateImage>(packet);
    auto it = images_.find(u.name);
    if (it == images_.end()) {
      problems_.push_back("update of '" + u.name + "', which was never created");
      return;
    }
    ReceivedImage& img = it->second;
    const net::TileRect& t = u.tile;
    if (t.x + t.width > img.width || t.y + t.height > img.height) {
      problems_.push_back("tile outside the image '" + u.name + "'");
      return;
    }
    for (size_t c = 0; c < u.channels.size(); ++c) {
      const int ch = img.channel(u.channels[c]);
      if (ch < 0) {
        problems_.push_back("update of channel '" + u.channels[c] + "', which '" + u.name + "' lacks");
        continue;
      }
      for (int y = 0; y < t.height; ++y)
        for (int x = 0; x < t.width; ++x)
          img.planes[size_t(ch)][size_t(t.y + y) * size_t(img.width) + size_t(t.x + x)] = u.at(c, x, y);
    }
    img.tiles.push_back({t, u.channels});
  }

  Mode mode_;
  int listener_ = -1;
  int port_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::map<std::string, ReceivedImage> images_;
  std::vector<std::string> problems_;
  int packets_ = 0, accepted_ = 0, ended_ = 0;
  std::vector<int> fillers_;  // BacklogFull: the fake's own connections
};

// The display server at 127.0.0.1:port.
inline net::DisplayServer serverAt(int port) {
  return net::resolveDisplayServer("127.0.0.1:" + std::to_string(port));
}

// A bound port nobody listens on (connections to it are refused while `fd` stays open).
inline int unusedPort(int& fd) {
  fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof a;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0)
    return -1;
  return ntohs(a.sin_port);
}

}  // namespace penumbra::test
