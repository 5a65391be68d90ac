#include "app/live/frame_server.h"

#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

namespace mostyle::live {
namespace {

constexpr auto kRefusalWarnEvery = std::chrono::seconds(1);

}  // namespace

FrameServer::FrameServer(const HostPort& where, const FrameServerOptions& options)
    : options_(options), where_(where) {
  options_.max_clients = std::max(1, options_.max_clients);
  ignore_sigpipe();
  listen_fd_ = listen_on(where, &where_.port);
}

FrameServer::~FrameServer() { close(); }

void FrameServer::close() {
  for (Client& c : clients_) ::close(c.fd);
  clients_.clear();
  if (listen_fd_ >= 0) ::close(listen_fd_);
  listen_fd_ = -1;
}

void FrameServer::add_poll_fds(std::vector<pollfd>* fds) const {
  // With no descriptors left, the listening socket stays readable: leave it for a few polls.
  fds->push_back({accept_pause_ > 0 ? -1 : listen_fd_, POLLIN, 0});
  for (const Client& c : clients_)
    fds->push_back({c.fd, static_cast<short>((c.read_closed ? 0 : POLLIN) | (c.waiting() > 0 ? POLLOUT : 0)), 0});
}

void FrameServer::handle_poll(const std::vector<pollfd>& fds, size_t first) {
  if (accept_pause_ > 0) --accept_pause_;
  const size_t polled = std::min(clients_.size(), fds.size() - first - 1);
  for (size_t i = 0; i < polled; ++i) {
    Client& c = clients_[i];
    const short events = fds[first + 1 + i].revents;
    if (events & (POLLHUP | POLLERR | POLLNVAL)) {
      drop(c, false);  // gone both ways, or reset
      continue;
    }
    if (events & POLLIN) {
      // Clients have nothing to say: what they send is read and ignored. One that closes its
      // sending side may still read (nc with no input does), so it stays until a send fails.
      char scratch[4096];
      const ssize_t n = ::recv(c.fd, scratch, sizeof scratch, 0);
      if (n == 0) c.read_closed = true;
      else if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) drop(c, false);
    }
    if (!c.gone && (events & POLLOUT)) flush(c);
  }
  remove_gone();
  // After the clients' hang-ups: a client that takes the place of one gone is not refused.
  if (fds[first].revents & POLLIN) accept_clients();
}

void FrameServer::accept_clients() {
  for (;;) {
    sockaddr_storage peer{};
    socklen_t length = sizeof peer;
    const int fd = ::accept4(listen_fd_, reinterpret_cast<sockaddr*>(&peer), &length, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) {
      if (errno == EMFILE || errno == ENFILE || errno == ENOBUFS || errno == ENOMEM) accept_pause_ = 10;
      return;  // EAGAIN: no more waiting; a client that left before accept: nothing to do
    }
    if (static_cast<int>(clients_.size()) >= options_.max_clients) {
      refuse(fd, peer);
      continue;
    }
    set_no_delay(fd);
    ::setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &options_.send_buffer_bytes, sizeof options_.send_buffer_bytes);
    Client c;
    c.fd = fd;
    clients_.push_back(std::move(c));
    ++accepted_;
  }
}

// Accepted only to be closed: left waiting, it would hold a place in the backlog and think it
// was served; closed, it sees the end of the stream at once.
void FrameServer::refuse(int fd, const sockaddr_storage& peer) {
  ::close(fd);
  ++refused_;
  if (!options_.warn) return;
  const auto now = std::chrono::steady_clock::now();
  if (refusal_warned_ && now - last_refusal_warning_ < kRefusalWarnEvery) return;
  refusal_warned_ = true;
  last_refusal_warning_ = now;
  options_.warn("refused a client from " + address_host(peer) + ": " + std::to_string(options_.max_clients) +
                " clients are connected, the most --max-clients allows (" + std::to_string(refused_) +
                " refused in all)");
}

void FrameServer::flush(Client& c) {
  while (c.waiting() > 0) {
    const ssize_t n = ::send(c.fd, c.queue.data() + c.head, c.waiting(), MSG_NOSIGNAL);
    if (n > 0) {
      c.head += static_cast<size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) break;
    drop(c, false);  // reset or gone
    return;
  }
  if (c.waiting() == 0) {
    c.queue.clear();
    c.head = 0;
  } else if (c.head > c.queue.size() / 2) {
    c.queue.erase(0, c.head);  // keeps the queue's memory within twice its bound
    c.head = 0;
  }
}

void FrameServer::send_to(Client& c, std::string_view line) {
  if (c.waiting() == 0) {
    // Straight to the socket: no added latency when the client keeps up.
    while (!line.empty()) {
      const ssize_t n = ::send(c.fd, line.data(), line.size(), MSG_NOSIGNAL);
      if (n > 0) {
        line.remove_prefix(static_cast<size_t>(n));
        continue;
      }
      if (n < 0 && errno == EINTR) continue;
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) break;
      drop(c, false);
      return;
    }
    if (line.empty()) return;
  }
  if (c.waiting() + line.size() > options_.max_queue_bytes) {
    drop(c, true);
    return;
  }
  c.queue.append(line.data(), line.size());
}

void FrameServer::send(std::string_view line) {
  for (Client& c : clients_) send_to(c, line);
  remove_gone();
}

bool FrameServer::flushed() const {
  return std::all_of(clients_.begin(), clients_.end(), [](const Client& c) { return c.waiting() == 0; });
}

void FrameServer::drop(Client& c, bool slow) {
  if (c.gone) return;
  ::close(c.fd);
  c.gone = true;
  if (slow) ++dropped_;
}

void FrameServer::remove_gone() {
  clients_.erase(std::remove_if(clients_.begin(), clients_.end(), [](const Client& c) { return c.gone; }),
                 clients_.end());
}

}  // namespace mostyle::live
