// `mostyle-cli live-send`: a take served as Axis Neuron serves its stream.
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "app/live/frame_server.h"
#include "app/live/live_run.h"
#include "app/live/stop_pipe.h"
#include "engine/live/axis_stream.h"

namespace mostyle::live {
namespace {

constexpr auto kDrainFor = std::chrono::seconds(5);  // the last frames to the clients

class LiveSend {
 public:
  LiveSend(const Clip& clip, const LiveSendConfig& config)
      : clip_(clip),
        config_(config),
        server_(config.serve, server_options(config)),
        rate_(config.rate > 0 ? config.rate : clip.fps()) {}

  int run(const std::string& source) {
    std::cout << "live-send: serving " << source << " (" << clip_.frames() << " frames at " << rate_
              << " fps) on " << server_.serving() << "; waiting for "
              << (config_.clients == 1 ? std::string("a client") : std::to_string(config_.clients) + " clients")
              << std::endl;
    if (wait_for_client()) send_frames();
    drain();
    std::cout << "live-send: " << sent_ << " frames sent; " << server_.accepted() << " clients, " << server_.dropped()
              << " dropped, " << server_.refused() << " refused" << std::endl;
    return 0;
  }

 private:
  static FrameServerOptions server_options(const LiveSendConfig& config) {
    FrameServerOptions options;
    options.max_clients = config.max_clients;
    options.warn = [](const std::string& sentence) { std::cerr << "mostyle: warning: " << sentence << "\n"; };
    return options;
  }

  // Polls the stop pipe and the server until `deadline`; false once stopped.
  bool serve_until(Clock::time_point deadline) {
    do {
      fds_.clear();
      fds_.push_back({stop_.fd(), POLLIN, 0});
      server_.add_poll_fds(&fds_);
      poll_until(&fds_, deadline);
      if (stop_.signal()) return false;
      server_.handle_poll(fds_, 1);
    } while (Clock::now() < deadline);
    return true;
  }

  bool wait_for_client() {
    while (server_.accepted() < config_.clients) {
      fds_.clear();
      fds_.push_back({stop_.fd(), POLLIN, 0});
      server_.add_poll_fds(&fds_);
      poll_until(&fds_, Clock::time_point::max());
      if (stop_.signal()) return false;
      server_.handle_poll(fds_, 1);
    }
    return true;
  }

  // Frame k leaves at t0 + k / rate: a late frame never delays the ones after it.
  void send_frames() {
    const Clock::time_point t0 = Clock::now();
    const int channels = clip_.skeleton.channel_count;
    for (long long k = 0; config_.loop || k < clip_.frames(); ++k) {
      const auto at = t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(k / rate_));
      if (!serve_until(at)) return;
      const double* row = clip_.motion.data() + (k % clip_.frames()) * channels;
      line_.clear();
      append_axis_line(&line_, 0, config_.avatar_name, nullptr, 0, row, channels);
      server_.send(line_);
      ++sent_;
    }
  }

  void drain() {
    const Clock::time_point until = Clock::now() + kDrainFor;
    while (!server_.flushed() && Clock::now() < until) {
      fds_.clear();
      fds_.push_back({stop_.fd(), POLLIN, 0});
      server_.add_poll_fds(&fds_);
      poll_until(&fds_, until);
      server_.handle_poll(fds_, 1);
    }
    server_.close();
  }

  const Clip& clip_;
  const LiveSendConfig& config_;
  StopPipe stop_;
  FrameServer server_;
  const double rate_;
  std::vector<pollfd> fds_;
  std::string line_;
  long long sent_ = 0;
};

}  // namespace

int run_live_send(const Clip& clip, const std::string& source, const LiveSendConfig& config) {
  return LiveSend(clip, config).run(source);
}

}  // namespace mostyle::live
