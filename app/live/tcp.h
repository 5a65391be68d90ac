#pragma once
// The few POSIX socket calls `mostyle-cli live` and `live-send` make, as small functions: a
// listening socket, a non-blocking connection, HOST:PORT. TCP over IPv6 and IPv4.
#include <poll.h>
#include <sys/socket.h>

#include <chrono>
#include <string>
#include <vector>

namespace mostyle::live {

struct HostPort {
  std::string host;  // a name or an address ("localhost", "192.168.1.20", "::1")
  int port = 0;      // 1 to 65535 (0 for a server: any free port)
  std::string text() const;  // "host:port" ("[::1]:7001" for an IPv6 address)
};

// Where a server listens unless told otherwise: this machine only, so that a performer's stream
// reaches the network only when asked.
inline constexpr const char* kDefaultServeHost = "127.0.0.1";

// "HOST:PORT", "[IPV6]:PORT" or ":PORT" (this machine). Throws InputError naming `flag` on
// anything else or a port outside 1 to 65535.
HostPort parse_host_port(const std::string& text, const std::string& flag);

// A server's address as typed: "PORT" (on kDefaultServeHost), "ADDRESS:PORT" or
// "[IPV6]:PORT", the address numeric (0.0.0.0: every IPv4 interface; [::]: every interface, IPv4
// too), the port 0 (any free one) to 65535. Throws InputError naming `flag` otherwise.
HostPort parse_serve_address(const std::string& text, const std::string& flag);

// Ignores SIGPIPE for the whole process: a client gone away is an error from send, not death.
void ignore_sigpipe();

// Makes `fd` non-blocking and close-on-exec.
void set_nonblocking(int fd);

// A non-blocking TCP socket listening on `where` (a numeric address, as parse_serve_address
// gives; "::" takes IPv4 too; port 0: one the system picks). Returns the socket and puts the port
// it got in *bound. Throws InputError "cannot serve on ADDRESS port P: reason".
int listen_on(const HostPort& where, int* bound);

// Where a server listens, for people: "127.0.0.1 port 7001 (this machine only)", "0.0.0.0 port
// 7001 (every IPv4 interface)", ":: port 7001 (every interface)", "192.168.1.20 port 7001".
std::string serving_text(const HostPort& where);

struct SocketAddress {
  sockaddr_storage storage{};
  socklen_t length = 0;
};

// The addresses HOST:PORT names, for TCP. Throws InputError "cannot find HOST: reason".
std::vector<SocketAddress> resolve(const HostPort& where);

// A socket address's numeric host ("192.168.1.7", "::1"; an IPv4-mapped one as IPv4).
std::string address_host(const sockaddr_storage& address);

// Starts a non-blocking connection to `address`. Returns the socket (connected, or connecting:
// poll it for POLLOUT, then ask connect_result) or -1 with errno set.
int start_connect(const SocketAddress& address);
// 0 once a connection started by start_connect succeeded, else its errno.
int connect_result(int fd);

// TCP_NODELAY on: each frame line leaves when it is sent, not when a packet fills.
void set_no_delay(int fd);

using Clock = std::chrono::steady_clock;
// poll(2) until `deadline` at the latest (to the nanosecond: ppoll), Clock::time_point::max()
// for none; a signal caught meanwhile ends it early. Returns poll's count (-1 with EINTR).
int poll_until(std::vector<pollfd>* fds, Clock::time_point deadline);

}  // namespace mostyle::live
