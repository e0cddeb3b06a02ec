#include "app/net/tev_client.h"

#include <arpa/inet.h>
#include <linux/sockios.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>

#include "app/net/tev_protocol.h"
#include "core/math/error.h"

namespace penumbra::net {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}
int pollMs(double seconds) {
  return seconds <= 0 ? 0 : int(seconds * 1e3) + 1;
}

// Longest single poll: how late a deadline set by another thread may be noticed.
constexpr int kSliceMs = 20;
const char* const kPastDeadline = "gave up at the deadline";

// RFC 1123 host names: dot-separated labels of letters, digits and inner hyphens, at most 63 each.
bool isHostName(const std::string& h) {
  if (h.empty() || h.size() > 253) return false;
  size_t label = 0;
  for (size_t i = 0; i <= h.size(); ++i) {
    if (i == h.size() || h[i] == '.') {
      if (label == 0 && i != h.size()) return false;  // empty label
      if (label > 63 || (label > 0 && h[i - 1] == '-')) return false;
      label = 0;
      continue;
    }
    const char c = h[i];
    const bool alnum = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    if (!alnum && !(c == '-' && label > 0)) return false;
    ++label;
  }
  return true;
}

}  // namespace

std::string DisplayServer::label() const {
  const bool v6 = host.find(':') != std::string::npos;
  return (v6 ? "[" + host + "]" : host) + ":" + std::to_string(port);
}

DisplayServer resolveDisplayServer(const std::string& spec) {
  const std::string where = "--display-server " + spec + ": ";
  DisplayServer s;
  std::string port;
  if (!spec.empty() && spec[0] == '[') {
    const size_t close = spec.find(']');
    if (close == std::string::npos) throw Error(where + "expected ']' after an IPv6 address");
    s.host = spec.substr(1, close - 1);
    if (close + 1 < spec.size()) {
      if (spec[close + 1] != ':') throw Error(where + "expected ':PORT' after ']'");
      port = spec.substr(close + 2);
      if (port.empty()) throw Error(where + "expected a port after ':'");
    }
    in6_addr a;
    if (inet_pton(AF_INET6, s.host.c_str(), &a) != 1)
      throw Error(where + "'" + s.host + "' is not an IPv6 address");
  } else {
    const size_t colon = spec.find(':');
    if (colon != std::string::npos && spec.find(':', colon + 1) != std::string::npos)
      throw Error(where + "expected HOST:PORT (write an IPv6 address in brackets: [::1]:14158)");
    s.host = spec.substr(0, colon);
    if (colon != std::string::npos) {
      port = spec.substr(colon + 1);
      if (port.empty()) throw Error(where + "expected a port after ':'");
    }
    if (s.host.empty()) throw Error(where + "expected HOST or HOST:PORT, e.g. 127.0.0.1:14158");
    if (!isHostName(s.host)) throw Error(where + "'" + s.host + "' is not a host name or IPv4 address");
  }
  s.port = kTevDefaultPort;
  if (!port.empty()) {
    if (port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos || std::stoi(port) < 1 ||
        std::stoi(port) > 65535)
      throw Error(where + "port '" + port + "': expected a number in 1..65535");
    s.port = uint16_t(std::stoi(port));
  }

  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  const int rc = getaddrinfo(s.host.c_str(), std::to_string(s.port).c_str(), &hints, &found);
  if (rc != 0) throw Error(where + "cannot resolve host '" + s.host + "': " + gai_strerror(rc));
  for (addrinfo* a = found; a; a = a->ai_next) {
    if (a->ai_addrlen > sizeof(sockaddr_storage)) continue;
    DisplayServer::Address addr;
    std::memcpy(&addr.storage, a->ai_addr, a->ai_addrlen);
    addr.length = a->ai_addrlen;
    addr.family = a->ai_family;
    s.addresses.push_back(addr);
  }
  freeaddrinfo(found);
  if (s.addresses.empty()) throw Error(where + "host '" + s.host + "' has no usable address");
  return s;
}

TevConnection::~TevConnection() {
  close();
}

void TevConnection::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void TevConnection::setDeadline(Clock::time_point deadline) {
  deadline_ = deadline.time_since_epoch().count();
}

void TevConnection::clearDeadline() {
  deadline_ = Clock::time_point::max().time_since_epoch().count();
}

bool TevConnection::pastDeadline() const {
  return Clock::now().time_since_epoch().count() >= deadline_.load();
}

int TevConnection::waitFor(int fd, short events, double seconds) {
  const auto began = Clock::now();
  for (;;) {
    if (pastDeadline()) {
      errno = 0;
      return -1;
    }
    const double left = seconds - secondsSince(began);
    if (left <= 0) return 0;
    pollfd p{fd, events, 0};
    const int rc = ::poll(&p, 1, std::min(pollMs(left), kSliceMs));
    if (rc > 0) return rc;
    if (rc < 0 && errno != EINTR) return -1;
  }
}

bool TevConnection::connect(const DisplayServer& server, double timeoutSeconds, std::string& why) {
  close();
  why = "no address to connect to";
  for (const DisplayServer::Address& a : server.addresses) {
    int fd = ::socket(a.family, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) {
      why = std::strerror(errno);
      continue;
    }
    int rc = ::connect(fd, reinterpret_cast<const sockaddr*>(&a.storage), a.length);
    if (rc != 0 && errno == EINPROGRESS) {
      rc = waitFor(fd, POLLOUT, timeoutSeconds);
      if (rc == 0) {
        why = "no answer within " + std::to_string(int(timeoutSeconds)) + " s";
        ::close(fd);
        continue;
      }
      if (rc < 0 && pastDeadline()) {
        why = kPastDeadline;
        ::close(fd);
        return false;
      }
      int err = 0;
      socklen_t len = sizeof err;
      if (rc < 0 || getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &len) != 0) err = errno;
      rc = err == 0 ? 0 : -1;
      errno = err;
    }
    if (rc != 0) {
      why = std::strerror(errno);
      ::close(fd);
      continue;
    }
    fd_ = fd;
    return true;
  }
  return false;
}

bool TevConnection::peerClosed() {
  if (fd_ < 0) return true;
  pollfd p{fd_, POLLIN | POLLRDHUP, 0};
  if (::poll(&p, 1, 0) <= 0) return false;
  uint8_t buf[256];
  // Bytes from tev (it sends none) are read and ignored; end of stream or an error means it has gone.
  const ssize_t n = ::recv(fd_, buf, sizeof buf, MSG_DONTWAIT);
  return n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR);
}

bool TevConnection::write(std::span<const uint8_t> bytes, double stallSeconds, std::string& why) {
  if (fd_ < 0) {
    why = "not connected";
    return false;
  }
  size_t sent = 0;
  while (sent < bytes.size()) {
    if (pastDeadline()) {
      why = kPastDeadline;
      close();
      return false;
    }
    const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n > 0) {
      sent += size_t(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK) {
      why = errno == EPIPE || errno == ECONNRESET ? "closed the connection" : std::strerror(errno);
      close();
      return false;
    }
    const int rc = waitFor(fd_, POLLOUT, stallSeconds);
    if (rc == 0) {
      why = "stopped reading (nothing taken for " + std::to_string(int(stallSeconds)) + " s)";
      close();
      return false;
    }
    if (rc < 0) {
      why = pastDeadline() ? kPastDeadline : std::strerror(errno);
      close();
      return false;
    }
  }
  return true;
}

bool TevConnection::finish(double timeoutSeconds, std::string& why) {
  if (fd_ < 0) {
    why = "not connected";
    return false;
  }
  if (peerClosed()) {  // before our end of stream: it left without reading everything
    why = "closed the connection";
    close();
    return false;
  }
  ::shutdown(fd_, SHUT_WR);
  // The timeout moves while the peer keeps taking bytes (SIOCOUTQ: sent but not yet acknowledged);
  // the deadline does not.
  int unacked = -1;
  auto lastProgress = Clock::now();
  uint8_t buf[4096];
  for (;;) {
    if (pastDeadline()) {
      why = kPastDeadline;
      close();
      return false;
    }
    int queued = 0;
    if (ioctl(fd_, SIOCOUTQ, &queued) == 0 && queued != unacked) {
      unacked = queued;
      lastProgress = Clock::now();
    }
    const double left = timeoutSeconds - secondsSince(lastProgress);
    if (left <= 0) {
      why = unacked > 0 ? "stopped reading before the end of the stream"
                        : "did not close the connection within " + std::to_string(int(timeoutSeconds)) +
                              " s of the end of the stream (it may not have read it)";
      close();
      return false;
    }
    pollfd p{fd_, POLLIN | POLLRDHUP, 0};
    const int rc = ::poll(&p, 1, std::min(pollMs(left), kSliceMs));
    if (rc <= 0) continue;  // timeout (re-check progress and the deadline) or EINTR
    const ssize_t n = ::recv(fd_, buf, sizeof buf, MSG_DONTWAIT);
    if (n == 0) break;  // the peer read to our end of stream and closed: everything arrived
    if (n < 0 && errno != EAGAIN && errno != EINTR) {
      why = errno == ECONNRESET || errno == EPIPE ? "closed the connection before reading everything"
                                                  : std::strerror(errno);
      close();
      return false;
    }
  }
  close();
  return true;
}

}  // namespace penumbra::net
