#include "app/editor/tcp_frame_source.h"

#include <fcntl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include "engine/base/error.h"

namespace mostyle::app {
namespace {

constexpr size_t kReadBytes = size_t{1} << 16;

}  // namespace

TcpFrameSource::TcpFrameSource(live::HostPort where) : where_(std::move(where)) {
  if (::pipe2(stop_pipe_, O_CLOEXEC | O_NONBLOCK) != 0)
    throw InputError(std::string("Live: cannot make a pipe: ") + std::strerror(errno));
}

TcpFrameSource::~TcpFrameSource() {
  if (fd_ >= 0) ::close(fd_);
  ::close(stop_pipe_[0]);
  ::close(stop_pipe_[1]);
}

void TcpFrameSource::stop() {
  stopped_ = true;
  const char byte = 1;
  [[maybe_unused]] const ssize_t n = ::write(stop_pipe_[1], &byte, 1);  // full: already woken
}

bool TcpFrameSource::wait_for(short events) {
  std::vector<pollfd> fds = {{fd_, events, 0}, {stop_pipe_[0], POLLIN, 0}};
  for (;;) {
    if (stopped_) return false;
    const int n = live::poll_until(&fds, live::Clock::time_point::max());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError(where_.text() + ": " + std::strerror(errno));
    if (fds[1].revents != 0 || stopped_) return false;
    if (fds[0].revents != 0) return true;
  }
}

void TcpFrameSource::open() {
  const std::vector<live::SocketAddress> addresses = live::resolve(where_);
  int error = ECONNREFUSED;
  for (const live::SocketAddress& address : addresses) {
    fd_ = live::start_connect(address);
    if (fd_ < 0) {
      error = errno;
      continue;
    }
    if (!wait_for(POLLOUT)) return;  // stopped
    error = live::connect_result(fd_);
    if (error == 0) {
      live::set_no_delay(fd_);
      return;
    }
    ::close(fd_);
    fd_ = -1;
  }
  throw InputError("cannot connect to " + where_.text() + ": " + std::strerror(error));
}

bool TcpFrameSource::read(std::string* bytes) {
  for (;;) {
    if (fd_ < 0 || !wait_for(POLLIN)) return false;
    bytes->resize(kReadBytes);
    const ssize_t n = ::recv(fd_, bytes->data(), bytes->size(), 0);
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) continue;
    if (n < 0 && errno == ECONNRESET) return false;  // closed by the server, abruptly
    if (n < 0) throw InputError(where_.text() + ": " + std::strerror(errno));
    if (n == 0) return false;
    bytes->resize(static_cast<size_t>(n));
    return true;
  }
}

std::unique_ptr<ui::FrameSource> make_tcp_frame_source(const std::string& address) {
  return std::make_unique<TcpFrameSource>(live::parse_host_port(address, "Live address"));
}

}  // namespace mostyle::app
