#pragma once
// A TCP server that sends each frame line to every client connected, as Axis Neuron does to the
// Perception Neuron plugins. Non-blocking throughout: a line goes straight to each client's
// socket; what the socket does not take waits in that client's own queue, sent as it drains. A
// client that stops reading is dropped when its queue would pass its bound, and never slows
// the others. It listens where it is told (this machine only unless the caller opens it) and
// serves a bounded number of clients, refusing the ones past it, so that neither the network
// nor a flood of connections gets more than asked. Run from one thread's poll loop
// (add_poll_fds, handle_poll).
#include <poll.h>

#include <chrono>
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "app/live/tcp.h"

namespace mostyle::live {

// The clients `live` and `live-send` serve at once unless --max-clients says otherwise: a few
// plugins, a recorder and a monitor, with room to spare.
inline constexpr int kDefaultMaxClients = 16;

struct FrameServerOptions {
  // The most bytes waiting for one client (about 2 s of a 59-joint Axis stream at 120 fps): past
  // it the client is dropped.
  size_t max_queue_bytes = size_t{1} << 20;
  // Each client socket's kernel send buffer (SO_SNDBUF): small, so that a slow client's frames
  // wait in its queue, where the bound sees them, not in the kernel.
  int send_buffer_bytes = 64 << 10;
  // The most clients served at once (at least 1). One more is accepted and closed at once, so
  // that connections never take every descriptor.
  int max_clients = kDefaultMaxClients;
  // Told of a client refused, in one sentence (who, why, how many so far), at most once a
  // second; none: nobody is told.
  std::function<void(const std::string&)> warn;
};

class FrameServer {
 public:
  // Listens on `where` (a numeric address; port 0: any free port). Throws InputError "cannot
  // serve on ADDRESS port P: reason".
  explicit FrameServer(const HostPort& where, const FrameServerOptions& options = {});
  ~FrameServer();  // closes every connection
  FrameServer(const FrameServer&) = delete;
  FrameServer& operator=(const FrameServer&) = delete;

  int port() const { return where_.port; }  // the port it got
  // Where it listens, for people (tcp.h serving_text): "127.0.0.1 port 7001 (this machine only)".
  std::string serving() const { return serving_text(where_); }

  // Appends the descriptors to poll: the listening socket (new clients) and each client (what
  // it sends is read and ignored; its hang-up; POLLOUT while its queue holds bytes).
  void add_poll_fds(std::vector<pollfd>* fds) const;
  // Accepts, reads, sends and closes as `fds` (from `first`, in add_poll_fds's order) say.
  void handle_poll(const std::vector<pollfd>& fds, size_t first);

  // Sends `line` to every client. O(clients) system calls at most.
  void send(std::string_view line);

  // No bytes wait in any queue.
  bool flushed() const;
  // Closes every client connection (each gets what the kernel holds, then the end of stream)
  // and stops listening.
  void close();

  int clients() const { return static_cast<int>(clients_.size()); }  // connected now
  long long accepted() const { return accepted_; }  // clients served since the start
  long long dropped() const { return dropped_; }    // clients dropped as they stopped reading
  long long refused() const { return refused_; }    // clients refused, past max_clients

 private:
  struct Client {
    int fd = -1;
    std::string queue;  // bytes not yet sent: queue[head..]
    size_t head = 0;
    bool read_closed = false;  // the client closed its sending side (it may still read)
    bool gone = false;         // closed; removed at the end of the call
    size_t waiting() const { return queue.size() - head; }
  };
  void accept_clients();
  void refuse(int fd, const sockaddr_storage& peer);
  void flush(Client& c);                  // sends what waits until the socket takes no more
  void send_to(Client& c, std::string_view line);
  void drop(Client& c, bool slow);
  void remove_gone();

  FrameServerOptions options_;
  int listen_fd_ = -1;
  HostPort where_;
  std::vector<Client> clients_;
  long long accepted_ = 0, dropped_ = 0, refused_ = 0;
  int accept_pause_ = 0;  // polls to skip the listening socket after running out of descriptors
  std::chrono::steady_clock::time_point last_refusal_warning_;
  bool refusal_warned_ = false;
};

}  // namespace mostyle::live
