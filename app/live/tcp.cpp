#include "app/live/tcp.h"

#include <arpa/inet.h>
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

HostPort parse_serve_address(const std::string& text, const std::string& flag) {
  const auto bad = [&](const std::string& why) {
    return InputError(flag + ": expected PORT or ADDRESS:PORT (7001 for this machine only, 0.0.0.0:7001 for every " +
                      "IPv4 interface, [::]:7001 for every interface), found '" + text + "': " + why);
  };
  HostPort r;
  r.host = kDefaultServeHost;
  std::string port_text = text;
  const size_t colon = text.rfind(':');
  if (colon != std::string::npos) {
    std::string host = text.substr(0, colon);
    port_text = text.substr(colon + 1);
    const bool bracketed = host.size() >= 2 && host.front() == '[' && host.back() == ']';
    if (bracketed) host = host.substr(1, host.size() - 2);
    // ":7001" means every interface to some tools and this machine to others: ask which.
    if (host.empty()) throw bad("give the address to listen on before ':'");
    unsigned char scratch[sizeof(in6_addr)];
    if (bracketed && ::inet_pton(AF_INET6, host.c_str(), scratch) != 1) throw bad("'" + host + "' is not an IPv6 address");
    if (!bracketed && ::inet_pton(AF_INET, host.c_str(), scratch) != 1)
      throw bad(host.find(':') != std::string::npos ? "an IPv6 address goes in brackets ([::1]:7001)"
                                                    : "'" + host + "' is not a numeric IPv4 address");
    r.host = host;
  }
  if (!parse_int(port_text, &r.port) || r.port < 0 || r.port > 65535)
    throw bad("the port is not a number from 0 (any free one) to 65535");
  return r;
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

int listen_on(const HostPort& where, int* bound) {
  const std::string host = where.host.find(':') != std::string::npos ? "[" + where.host + "]" : where.host;
  const auto fail = [&](int error) {
    return InputError("cannot serve on " + host + " port " + std::to_string(where.port) + ": " + std::strerror(error));
  };
  sockaddr_storage address{};
  socklen_t length = 0;
  const uint16_t port = htons(static_cast<uint16_t>(where.port));
  auto* a6 = reinterpret_cast<sockaddr_in6*>(&address);
  auto* a4 = reinterpret_cast<sockaddr_in*>(&address);
  if (::inet_pton(AF_INET6, where.host.c_str(), &a6->sin6_addr) == 1) {
    a6->sin6_family = AF_INET6;
    a6->sin6_port = port;
    length = sizeof *a6;
  } else if (::inet_pton(AF_INET, where.host.c_str(), &a4->sin_addr) == 1) {
    a4->sin_family = AF_INET;
    a4->sin_port = port;
    length = sizeof *a4;
  } else {
    throw InputError("cannot serve on " + where.host + ": expected a numeric address (127.0.0.1, 0.0.0.0, ::)");
  }
  const int fd = ::socket(address.ss_family, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) throw fail(errno);
  const auto close_and_fail = [&](int error) {
    ::close(fd);
    return fail(error);
  };
  const int on = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
  if (address.ss_family == AF_INET6 && IN6_IS_ADDR_UNSPECIFIED(&a6->sin6_addr)) {
    // "::" is every interface, IPv4 ones too, whatever the system's default for IPv6 sockets.
    const int off = 0;
    ::setsockopt(fd, IPPROTO_IPV6, IPV6_V6ONLY, &off, sizeof off);
  }
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&address), length) != 0) throw close_and_fail(errno);
  if (::listen(fd, 64) != 0) throw close_and_fail(errno);
  sockaddr_storage s{};
  socklen_t bound_length = sizeof s;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&s), &bound_length);
  *bound = s.ss_family == AF_INET6 ? ntohs(reinterpret_cast<sockaddr_in6*>(&s)->sin6_port)
                                   : ntohs(reinterpret_cast<sockaddr_in*>(&s)->sin_port);
  return fd;
}

std::string serving_text(const HostPort& where) {
  const bool v6 = where.host.find(':') != std::string::npos;
  std::string text = (v6 ? "[" + where.host + "]" : where.host) + " port " + std::to_string(where.port);
  in_addr a4{};
  in6_addr a6{};
  if (::inet_pton(AF_INET, where.host.c_str(), &a4) == 1) {
    if ((ntohl(a4.s_addr) >> 24) == 127) return text + " (this machine only)";
    if (a4.s_addr == htonl(INADDR_ANY)) return text + " (every IPv4 interface)";
  } else if (::inet_pton(AF_INET6, where.host.c_str(), &a6) == 1) {
    if (IN6_IS_ADDR_LOOPBACK(&a6)) return text + " (this machine only)";
    if (IN6_IS_ADDR_UNSPECIFIED(&a6)) return text + " (every interface)";
  }
  return text;
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

std::string address_host(const sockaddr_storage& address) {
  char host[NI_MAXHOST] = "?";
  const socklen_t length = address.ss_family == AF_INET6 ? sizeof(sockaddr_in6) : sizeof(sockaddr_in);
  ::getnameinfo(reinterpret_cast<const sockaddr*>(&address), length, host, sizeof host, nullptr, 0, NI_NUMERICHOST);
  const std::string text = host;
  const std::string mapped = "::ffff:";
  if (text.rfind(mapped, 0) == 0 && text.find('.') != std::string::npos) return text.substr(mapped.size());
  return text;
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
