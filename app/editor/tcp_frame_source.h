#pragma once
// The editor's live source over TCP (ui/model/live_source.h FrameSource): a connection to a BVH
// broadcasting server (Axis Neuron, Axis Studio, `mostyle-cli live-send`), made and read with
// app/live/tcp.h's calls. Blocking reads that stop() interrupts at once (a pipe polled beside
// the socket).
#include <atomic>
#include <memory>
#include <string>

#include "app/live/tcp.h"
#include "ui/model/live_source.h"

namespace mostyle::app {

class TcpFrameSource : public ui::FrameSource {
 public:
  explicit TcpFrameSource(live::HostPort where);
  ~TcpFrameSource() override;
  TcpFrameSource(const TcpFrameSource&) = delete;
  TcpFrameSource& operator=(const TcpFrameSource&) = delete;

  // Tries each address the host names in turn. Throws InputError "cannot find HOST: ..." or
  // "cannot connect to HOST:PORT: reason".
  void open() override;
  // Up to 64 KB as they come; false once the server closes (or after stop()). Throws InputError
  // "HOST:PORT: reason" on a read error.
  bool read(std::string* bytes) override;
  void stop() override;

 private:
  // Polls the socket for `events` beside the stop pipe: false once stopped.
  bool wait_for(short events);

  live::HostPort where_;
  int fd_ = -1;
  int stop_pipe_[2] = {-1, -1};
  std::atomic<bool> stopped_{false};
};

// A TcpFrameSource for an address as typed ("HOST:PORT", "[::1]:7001", ":7001"). Throws
// InputError "Live address: expected HOST:PORT ..." otherwise.
std::unique_ptr<ui::FrameSource> make_tcp_frame_source(const std::string& address);

}  // namespace mostyle::app
