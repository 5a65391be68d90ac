#pragma once
// Helpers for tests of `mostyle-cli live` and `live-send`: the built mostyle-cli (MOSTYLE_CLI) run
// as a child process whose stdout the test reads as it comes (the port it prints), TCP sockets on
// loopback (ports picked by the system), and reading lines with generous deadlines, so that a
// loaded two-core machine slows the tests down but never fails them.
#include <arpa/inet.h>
#include <dirent.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <functional>
#include <regex>
#include <stdexcept>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

namespace mostyle::test {

using TestClock = std::chrono::steady_clock;
// Long enough for a loaded machine; a test that waits this long has failed anyway.
constexpr auto kLiveTimeout = std::chrono::seconds(60);

// mostyle-cli with `args`, stdout a pipe read by the test, stderr a file.
class CliProcess {
 public:
  CliProcess(const std::vector<std::string>& args, const std::string& stderr_path) {
    // Everything the child needs is made before fork: after it, only system calls.
    std::vector<std::string> words{MOSTYLE_CLI};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    int out[2];
    if (::pipe2(out, O_CLOEXEC) != 0) throw std::runtime_error("pipe");
    const int err = ::open(stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(out[1], 1);
      ::dup2(err, 2);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    ::close(err);
    ::close(out[1]);
    out_fd_ = out[0];
    stderr_path_ = stderr_path;
  }
  ~CliProcess() {
    if (pid_ > 0 && status_ == kRunning) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    if (out_fd_ >= 0) ::close(out_fd_);
  }
  CliProcess(const CliProcess&) = delete;
  CliProcess& operator=(const CliProcess&) = delete;

  // Reads stdout until a line says "port N"; returns N, or -1 when the process ended first.
  int port() {
    const std::regex pattern("port ([0-9]+)");
    for (;;) {
      std::smatch m;
      if (std::regex_search(out_, m, pattern)) {
        const int port = std::stoi(m[1]);
        // m points into out_: take everything from it before out_ changes.
        seen_ += m.prefix().str() + m.str();
        std::string rest = m.suffix().str();
        out_ = std::move(rest);
        return port;
      }
      if (!read_some(TestClock::now() + kLiveTimeout)) return -1;
    }
  }

  // Reads stdout until it holds `text`; false if it has not within kLiveTimeout.
  bool wait_for_output(const std::string& text) {
    const auto deadline = TestClock::now() + kLiveTimeout;
    while (out().find(text) == std::string::npos)
      if (!read_some(deadline)) return false;
    return true;
  }

  // Waits for the exit (killing it after kLiveTimeout); returns the exit status, or -1 when a
  // signal ended it. Collects the rest of stdout.
  int wait() {
    const auto deadline = TestClock::now() + kLiveTimeout;
    while (read_some(deadline)) {
    }
    if (status_ == kRunning) {
      int raw = 0;
      while (::waitpid(pid_, &raw, WNOHANG) == 0) {
        if (TestClock::now() > deadline) ::kill(pid_, SIGKILL);
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
      status_ = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    }
    return status_;
  }

  void signal(int sig) { ::kill(pid_, sig); }
  pid_t pid() const { return pid_; }
  std::string out() const { return seen_ + out_; }
  std::string err() const {
    std::FILE* f = std::fopen(stderr_path_.c_str(), "rb");
    std::string s;
    if (!f) return s;
    char buffer[4096];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) s.append(buffer, n);
    std::fclose(f);
    return s;
  }

 private:
  static constexpr int kRunning = -2;
  // One read of stdout; false at its end or the deadline.
  bool read_some(TestClock::time_point deadline) {
    pollfd p{out_fd_, POLLIN, 0};
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - TestClock::now()).count();
    if (left <= 0 || ::poll(&p, 1, static_cast<int>(left)) <= 0) return false;
    char buffer[4096];
    const ssize_t n = ::read(out_fd_, buffer, sizeof buffer);
    if (n <= 0) return false;
    out_.append(buffer, static_cast<size_t>(n));
    return true;
  }

  pid_t pid_ = -1;
  int out_fd_ = -1;
  int status_ = kRunning;
  std::string out_, seen_, stderr_path_;
};

// A TCP connection to 127.0.0.1:port (blocking), with a receive buffer of `receive_buffer` bytes
// when that is above 0 (set before connecting, so that the window stays small).
inline int connect_local(int port, int receive_buffer = 0) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (receive_buffer > 0) ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &receive_buffer, sizeof receive_buffer);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(static_cast<uint16_t>(port));
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

// A listening socket on 127.0.0.1 (port picked by the system); its port in *port.
inline int listen_local(int* port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  ::listen(fd, 8);
  socklen_t length = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &length);
  *port = ntohs(a.sin_port);
  return fd;
}

// A socket bound to 127.0.0.1:port (0: picked by the system), SO_REUSEADDR (the port of a source
// closed a moment ago); its port in *bound. -1 if it cannot be bound.
inline int bound_local(int port, int* bound) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  const int on = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(static_cast<uint16_t>(port));
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  socklen_t length = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &length);
  *bound = ntohs(a.sin_port);
  return fd;
}

// A socket bound to 127.0.0.1 (port picked by the system, in *port) and not listening:
// connections to it are refused until the test calls listen().
inline int bound_not_listening(int* port) { return bound_local(0, port); }

// Listening on 127.0.0.1:port again (SO_REUSEADDR: the port of a source closed a moment ago);
// -1 if it cannot.
inline int listen_local_on(int port) {
  int bound = 0;
  const int fd = bound_local(port, &bound);
  if (fd >= 0 && ::listen(fd, 8) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

// The address a TCP socket listening on `port` is bound to, as the kernel lists it
// (/proc/net/tcp, then tcp6): "127.0.0.1", "0.0.0.0", "::" ...; "" when none listens there. No
// traffic: a socket bound to a loopback address is one no other machine can reach, which is what
// the tests need to know without sending anything to an interface's address.
inline std::string listening_address(int port) {
  for (const char* table : {"/proc/net/tcp", "/proc/net/tcp6"}) {
    std::FILE* f = std::fopen(table, "r");
    if (f == nullptr) continue;
    char line[512];
    std::string found;
    while (found.empty() && std::fgets(line, sizeof line, f)) {
      char local[64] = "", remote[64] = "", state[8] = "";
      unsigned slot = 0;
      if (std::sscanf(line, " %u: %63s %63s %7s", &slot, local, remote, state) != 4) continue;
      const std::string l = local;
      const size_t colon = l.rfind(':');
      if (colon == std::string::npos || std::string(state) != "0A") continue;  // 0A: LISTEN
      if (std::stoi(l.substr(colon + 1), nullptr, 16) != port) continue;
      const std::string hex = l.substr(0, colon);
      if (hex.size() == 8) {
        in_addr a{};
        a.s_addr = static_cast<in_addr_t>(std::stoul(hex, nullptr, 16));  // the kernel's byte order
        char text[INET_ADDRSTRLEN] = "";
        ::inet_ntop(AF_INET, &a, text, sizeof text);
        found = text;
      } else if (hex.size() == 32) {
        in6_addr a{};
        for (int w = 0; w < 4; ++w) {
          const uint32_t word = static_cast<uint32_t>(std::stoul(hex.substr(8 * w, 8), nullptr, 16));
          std::memcpy(a.s6_addr + 4 * w, &word, 4);
        }
        char text[INET6_ADDRSTRLEN] = "";
        ::inet_ntop(AF_INET6, &a, text, sizeof text);
        found = text;
      }
    }
    std::fclose(f);
    if (!found.empty()) return found;
  }
  return std::string();
}

// An address of the loopback range other than 127.0.0.1 (Linux answers the whole 127.0.0.0/8 on
// lo): a server bound to it alone is refused by 127.0.0.1, as one bound to an interface's address
// is by every other, with nothing leaving this machine.
inline in_addr other_loopback() {
  in_addr a{};
  a.s_addr = htonl(0x7F000002u);  // 127.0.0.2
  return a;
}

// A blocking TCP connection to address:port (a loopback address: never another machine's); -1
// with errno set when refused.
inline int connect_to(in_addr address, int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr = address;
  a.sin_port = htons(static_cast<uint16_t>(port));
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    const int e = errno;
    ::close(fd);
    errno = e;
    return -1;
  }
  return fd;
}

inline std::string address_text(in_addr address) {
  char text[INET_ADDRSTRLEN] = "";
  ::inet_ntop(AF_INET, &address, text, sizeof text);
  return text;
}

// The descriptors a process has open (/proc/PID/fd; "self" for this one).
inline int open_descriptors(const std::string& pid = "self") {
  DIR* d = ::opendir(("/proc/" + pid + "/fd").c_str());
  if (d == nullptr) return -1;
  int n = 0;
  while (const dirent* e = ::readdir(d))
    if (e->d_name[0] != '.') ++n;
  ::closedir(d);
  return pid == "self" ? n - 1 : n;  // not the one opendir holds
}

// Accepts one connection within kLiveTimeout; -1 if none came.
inline int accept_within(int listen_fd) {
  pollfd p{listen_fd, POLLIN, 0};
  if (::poll(&p, 1, static_cast<int>(std::chrono::milliseconds(kLiveTimeout).count())) <= 0) return -1;
  return ::accept4(listen_fd, nullptr, nullptr, SOCK_CLOEXEC);
}

inline bool send_all(int fd, const std::string& bytes) {
  size_t at = 0;
  while (at < bytes.size()) {
    const ssize_t n = ::send(fd, bytes.data() + at, bytes.size() - at, MSG_NOSIGNAL);
    if (n <= 0) return false;
    at += static_cast<size_t>(n);
  }
  return true;
}

// Reads lines from `fd` until `count` lines came, no more (count < 0: until the end of the stream) or
// kLiveTimeout passed; `on_lines`, when given, hears how many have come after each read.
inline std::vector<std::string> read_lines(int fd, long long count = -1,
                                           const std::function<void(size_t)>& on_lines = {}) {
  std::vector<std::string> lines;
  std::string partial;
  const auto deadline = TestClock::now() + kLiveTimeout;
  char buffer[1 << 16];
  while (count < 0 || static_cast<long long>(lines.size()) < count) {
    pollfd p{fd, POLLIN, 0};
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - TestClock::now()).count();
    if (left <= 0 || ::poll(&p, 1, static_cast<int>(left)) <= 0) break;
    // With a count, only the bytes up to the line that completes it are taken (looked at first,
    // then read), so that the next read starts at the next line, not inside it.
    ssize_t n = ::recv(fd, buffer, sizeof buffer, count < 0 ? 0 : MSG_PEEK);
    if (n <= 0) break;
    if (count >= 0) {
      long long wanted = count - static_cast<long long>(lines.size());
      ssize_t upto = n;
      for (ssize_t i = 0; i < n; ++i)
        if (buffer[i] == '\n' && --wanted == 0) {
          upto = i + 1;
          break;
        }
      n = ::recv(fd, buffer, static_cast<size_t>(upto), 0);
      if (n <= 0) break;
    }
    partial.append(buffer, static_cast<size_t>(n));
    size_t start = 0;
    for (size_t nl; (nl = partial.find('\n', start)) != std::string::npos; start = nl + 1)
      lines.push_back(partial.substr(start, nl - start));
    partial.erase(0, start);
    if (on_lines) on_lines(lines.size());
  }
  return lines;
}

// Waits until `done()` holds, checking every 10 ms, for kLiveTimeout at most.
template <typename Done>
bool eventually(Done done) {
  const auto deadline = TestClock::now() + kLiveTimeout;
  while (!done()) {
    if (TestClock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

}  // namespace mostyle::test
