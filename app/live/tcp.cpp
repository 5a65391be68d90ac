#include "app/live/tcp.h"

#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>

#include "engine/base/error.h"

namespace mostyle::live {
namespace {

bool parse_int(const std::string& text, int* value) {
  const auto r = std::from_chars(text.data(), text.data() + text.size(), *value);
  return !text.empty() && r.ec == std::errc() && r.ptr == text.data() + text.size();
}

}  // namespace

std::string HostPort::text() const {
  const std::string h = host.find(':') != std::string::npos ? "[" + host + "]" : host;
  return h + ":" + std::to_string(port);
}

HostPort parse_host_port(const std::string& text, const std::string& flag) {
  const size_t colon = text.rfind(':');
  const auto bad = [&](const std::string& why) {
    return InputError(flag + ": expected HOST:PORT (e.g. localhost:7001), found '" + text + "': " + why);
  };
  if (colon == std::string::npos) throw bad("no ':PORT'");
  HostPort r;
  r.host = text.substr(0, colon);
  if (r.host.size() >= 2 && r.host.front() == '[' && r.host.back() == ']') r.host = r.host.substr(1, r.host.size() - 2);
  if (r.host.empty()) r.host = "localhost";
  if (!parse_int(text.substr(colon + 1), &r.port) || r.port < 1 || r.port > 65535)
    throw bad("the port is not a number from 1 to 65535");
  return r;
}

int parse_port(const std::string& text, const std::string& flag) {
  int port = -1;
  if (!parse_int(text, &port) || port < 0 || port > 65535)
    throw InputError(flag + ": expected a port from 0 (any free one) to 65535, found '" + text + "'");
  return port;
}

void ignore_sigpipe() { ::signal(SIGPIPE, SIG_IGN); }

void set_nonblocking(int fd) {
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
  ::fcntl(fd, F_SETFD, ::fcntl(fd, F_GETFD) | FD_CLOEXEC);
}

void set_no_delay(int fd) {
  const int on = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
}

int listen_on(int port, int* bound) {
  const auto fail = [&](int error) {
    return InputError("cannot serve on port " + std::to_string(port) + ": " + std::strerror(error));
  };
  const int on = 1, off = 0;
  // IPv6 with IPv4-mapped addresses takes both; a system without IPv6 gets IPv4 alone.
  int fd = ::socket(AF_INET6, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd >= 0) {
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
    ::setsockopt(fd, IPPROTO_IPV6, IPV6_V6ONLY, &off, sizeof off);
    sockaddr_in6 a{};
    a.sin6_family = AF_INET6;
    a.sin6_addr = in6addr_any;
    a.sin6_port = htons(static_cast<uint16_t>(port));
    if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
      const int e = errno;
      ::close(fd);
      if (e != EAFNOSUPPORT && e != EADDRNOTAVAIL) throw fail(e);
      fd = -1;
    }
  }
  if (fd < 0) {
    fd = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) throw fail(errno);
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_ANY);
    a.sin_port = htons(static_cast<uint16_t>(port));
    if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
      const int e = errno;
      ::close(fd);
      throw fail(e);
    }
  }
  if (::listen(fd, 64) != 0) {
    const int e = errno;
    ::close(fd);
    throw fail(e);
  }
  sockaddr_storage s{};
  socklen_t length = sizeof s;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&s), &length);
  *bound = s.ss_family == AF_INET6 ? ntohs(reinterpret_cast<sockaddr_in6*>(&s)->sin6_port)
                                   : ntohs(reinterpret_cast<sockaddr_in*>(&s)->sin_port);
  return fd;
}

std::vector<SocketAddress> resolve(const HostPort& where) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* list = nullptr;
  const int r = ::getaddrinfo(where.host.c_str(), std::to_string(where.port).c_str(), &hints, &list);
  if (r != 0) throw InputError("cannot find " + where.host + ": " + ::gai_strerror(r));
  std::vector<SocketAddress> out;
  for (const addrinfo* a = list; a; a = a->ai_next) {
    SocketAddress s;
    std::memcpy(&s.storage, a->ai_addr, a->ai_addrlen);
    s.length = a->ai_addrlen;
    out.push_back(s);
  }
  ::freeaddrinfo(list);
  return out;
}

int start_connect(const SocketAddress& address) {
  const int fd = ::socket(address.storage.ss_family, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) return -1;
  set_no_delay(fd);
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&address.storage), address.length) == 0 ||
      errno == EINPROGRESS)
    return fd;
  const int e = errno;
  ::close(fd);
  errno = e;
  return -1;
}

int poll_until(std::vector<pollfd>* fds, Clock::time_point deadline) {
  if (deadline == Clock::time_point::max()) return ::ppoll(fds->data(), fds->size(), nullptr, nullptr);
  const auto left = std::max(Clock::duration::zero(), deadline - Clock::now());
  const long long ns = std::chrono::duration_cast<std::chrono::nanoseconds>(left).count();
  const timespec t{static_cast<time_t>(ns / 1'000'000'000), static_cast<long>(ns % 1'000'000'000)};
  return ::ppoll(fds->data(), fds->size(), &t, nullptr);
}

int connect_result(int fd) {
  int error = 0;
  socklen_t length = sizeof error;
  if (::getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &length) != 0) return errno;
  return error;
}

}  // namespace mostyle::live
