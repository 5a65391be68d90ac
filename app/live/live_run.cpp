#include "app/live/live_run.h"

#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <iostream>
#include <optional>
#include <sstream>
#include <vector>

#include "app/live/frame_server.h"
#include "app/live/stop_pipe.h"
#include "engine/base/error.h"
#include "engine/live/axis_stream.h"
#include "engine/live/stream_styler.h"

namespace mostyle::live {
namespace {

// A source not there is tried again after kFirstRetry, the wait doubling up to kLongestRetry: a
// mocap program restarting is found within a few seconds without a flood of attempts.
constexpr auto kFirstRetry = std::chrono::milliseconds(250);
constexpr auto kLongestRetry = std::chrono::seconds(2);
// One attempt's handshake at most: a host that drops the attempt (down, a firewall) is tried
// again instead of being waited for as long as the kernel would.
constexpr auto kAttemptFor = std::chrono::seconds(2);
constexpr auto kWarnEvery = std::chrono::seconds(1);           // skipped-frame warnings at most this often
constexpr auto kDrainFor = std::chrono::seconds(2);            // clients' queues at the end
constexpr size_t kReadBytes = size_t{1} << 16;

// The stream's lines come back here from the engine's loop (StreamStyler): served, recorded,
// counted, warned about.
class LiveRun : StreamStyler::Sink {
 public:
  LiveRun(LiveConfig& config, LiveStyle& style)
      : config_(config), style_(style), channels_(config.skeleton.channel_count), stream_(channels_) {}

  int run() {
    ignore_sigpipe();
    open_server();
    addresses_ = resolve(config_.source);
    start_waiting();
    start_connecting();
    while (!stop_.signal() && state_ != State::kDone) poll_once();
    finish();
    return 0;
  }

 private:
  enum class State { kWaiting, kConnecting, kConnected, kDone };

  // The server first, so that clients may connect while the source is awaited.
  void open_server() {
    if (!config_.serve) return;
    FrameServerOptions options;
    options.max_clients = config_.max_clients;
    options.warn = [](const std::string& sentence) { std::cerr << "mostyle: warning: " << sentence << "\n"; };
    server_.emplace(*config_.serve, options);
    std::cout << "live: serving on " << server_->serving() << std::endl;
  }

  bool waits_for_ever() const { return config_.connect_timeout_s < 0.0; }

  // The source is awaited from now: at the start, or once it closed.
  void start_waiting() {
    retry_in_ = kFirstRetry;
    give_up_at_ = waits_for_ever() ? Clock::time_point::max()
                                   : Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                        std::chrono::duration<double>(config_.connect_timeout_s));
  }

  // Tries the source's addresses in turn from address_; a refusal moves to the next.
  void start_connecting() {
    for (; address_ < addresses_.size(); ++address_) {
      source_fd_ = start_connect(addresses_[address_]);
      if (source_fd_ >= 0) {
        state_ = State::kConnecting;
        attempt_until_ = Clock::now() + kAttemptFor;
        return;
      }
      last_error_ = errno;
    }
    attempt_failed();
  }

  // Every address refused: wait and try again, said once until a connection comes, or give up
  // once the timeout has passed.
  void attempt_failed() {
    address_ = 0;
    const Clock::time_point now = Clock::now();
    if (now >= give_up_at_) return give_up();
    if (!waiting_noted_) {
      std::cerr << "mostyle: note: waiting for " << config_.source.text() << " (" << std::strerror(last_error_)
                << ")\n";
      waiting_noted_ = true;
    }
    wait_to_retry();
  }

  void wait_to_retry() {
    state_ = State::kWaiting;
    retry_at_ = std::min(give_up_at_, Clock::now() + retry_in_);
    retry_in_ = std::min<Clock::duration>(2 * retry_in_, kLongestRetry);
  }

  void give_up() {
    const std::string within = config_.connect_timeout_s > 0.0
                                   ? " within " + format_seconds(config_.connect_timeout_s) + " s (--connect-timeout)"
                                   : "";
    if (!connected_once_)
      throw InputError("cannot connect to " + config_.source.text() + within + ": " + std::strerror(last_error_));
    if (!within.empty()) std::cerr << "mostyle: note: " << config_.source.text() << " did not come back" << within << "\n";
    state_ = State::kDone;
  }

  static std::string format_seconds(double s) {
    std::ostringstream out;
    out << s;
    return out.str();
  }

  void poll_once() {
    fds_.clear();
    fds_.push_back({stop_.fd(), POLLIN, 0});
    const bool polling_source = state_ == State::kConnecting || state_ == State::kConnected;
    fds_.push_back({polling_source ? source_fd_ : -1, static_cast<short>(state_ == State::kConnecting ? POLLOUT : POLLIN), 0});
    const size_t server_at = fds_.size();
    if (server_) server_->add_poll_fds(&fds_);
    const Clock::time_point deadline = state_ == State::kWaiting      ? retry_at_
                                       : state_ == State::kConnecting ? attempt_until_
                                                                      : Clock::time_point::max();
    if (poll_until(&fds_, deadline) < 0 && errno != EINTR) throw std::runtime_error(std::strerror(errno));
    if (fds_[0].revents) return;  // stopped
    if (server_) server_->handle_poll(fds_, server_at);
    if (polling_source && fds_[1].revents) {
      if (state_ == State::kConnecting) finish_connecting();
      else read_source();
    } else if (state_ == State::kConnecting && Clock::now() >= attempt_until_) {
      next_address(ETIMEDOUT);
    }
    if (state_ == State::kWaiting && Clock::now() >= retry_at_) start_connecting();
  }

  // This address failed (its errno): the next one, or a wait.
  void next_address(int error) {
    ::close(source_fd_);
    source_fd_ = -1;
    last_error_ = error;
    ++address_;
    start_connecting();
  }

  void finish_connecting() {
    const int error = connect_result(source_fd_);
    if (error != 0) return next_address(error);
    state_ = State::kConnected;
    waiting_noted_ = false;
    // A new connection is a new stream (the mocap program restarted, maybe the performer
    // elsewhere, another avatar first): nothing of the last one carries over.
    if (connected_once_) style_.restart();
    connected_once_ = true;
    stream_.restart();
    lines_before_ = lines_in_;
    std::cerr << "mostyle: note: connected to " << config_.source.text() << "\n";
  }

  // One read, and every complete line in it styled and sent before the next read.
  void read_source() {
    buffer_.resize(kReadBytes);
    const ssize_t n = ::recv(source_fd_, buffer_.data(), buffer_.size(), 0);
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return;
    if (n <= 0) {
      source_closed();
      return;
    }
    stream_.feed(std::string_view(buffer_.data(), static_cast<size_t>(n)), *this);
  }

  LiveStyle& styler() override { return style_; }

  void styled(const AxisFrame& frame, const double* values) override {
    ++lines_in_;
    ++styled_;
    if (server_) {
      line_out_.clear();
      append_axis_line(&line_out_, frame.avatar_index, frame.avatar_name, frame.reference.data(),
                       static_cast<int>(frame.reference.size()), values, channels_);
      server_->send(line_out_);
    }
    // After the send: a recording's writes never delay the frame they hold.
    record(&config_.record, values);
    record(&config_.record_input, frame.values.data());
  }

  static void record(std::unique_ptr<BvhRecorder>* recorder, const double* values) {
    const std::string stopped = append_or_stop(recorder, values);
    if (!stopped.empty()) std::cerr << "mostyle: warning: " << stopped << "\n";
  }

  // Counts a frame skipped; warns at most once a second (one sentence: where, what, how many).
  void skipped(long long line, const std::string& why) override {
    ++lines_in_;
    ++skipped_;
    const Clock::time_point now = Clock::now();
    if (warned_ && now - last_warning_ < kWarnEvery) return;
    warned_ = true;
    last_warning_ = now;
    std::cerr << "mostyle: warning: " << config_.source.text() << " line " << line << ": " << why
              << "; frame skipped (" << skipped_ << " skipped in all)\n";
  }

  void source_closed() {
    stream_.end(*this);
    ::close(source_fd_);
    source_fd_ = -1;
    if (config_.connect_timeout_s == 0.0) {  // one try: the stream's end is the end
      state_ = State::kDone;
      return;
    }
    std::cerr << "mostyle: note: " << config_.source.text() << " closed after " << lines_in_ - lines_before_
              << " lines; waiting for it again\n";
    waiting_noted_ = true;
    last_error_ = ECONNRESET;
    start_waiting();
    wait_to_retry();
  }

  // The clients get what waits for them (a few seconds at most), then the end of the stream.
  void finish() {
    if (source_fd_ >= 0) ::close(source_fd_);
    source_fd_ = -1;
    if (server_) {
      const Clock::time_point until = Clock::now() + kDrainFor;
      while (!server_->flushed() && Clock::now() < until) {
        fds_.clear();
        fds_.push_back({stop_.fd(), POLLIN, 0});
        server_->add_poll_fds(&fds_);
        poll_until(&fds_, until);
        server_->handle_poll(fds_, 1);
      }
      server_->close();
    }
    config_.record.reset();
    config_.record_input.reset();
    std::cout << "live: " << lines_in_ << " frames in, " << styled_ << " styled, " << skipped_ << " skipped; "
              << (server_ ? server_->accepted() : 0) << " clients, " << (server_ ? server_->dropped() : 0)
              << " dropped, " << (server_ ? server_->refused() : 0) << " refused" << std::endl;
  }

  LiveConfig& config_;
  LiveStyle& style_;
  const int channels_;
  StopPipe stop_;
  std::optional<FrameServer> server_;
  std::vector<SocketAddress> addresses_;
  size_t address_ = 0;
  int last_error_ = 0;
  State state_ = State::kWaiting;
  int source_fd_ = -1;
  bool connected_once_ = false, waiting_noted_ = false;
  Clock::time_point retry_at_, attempt_until_, give_up_at_;
  Clock::duration retry_in_ = kFirstRetry;
  std::vector<pollfd> fds_;
  std::vector<char> buffer_;
  StreamStyler stream_;
  std::string line_out_;
  long long lines_in_ = 0, lines_before_ = 0, styled_ = 0, skipped_ = 0;
  bool warned_ = false;
  Clock::time_point last_warning_;
};

}  // namespace

int run_live(LiveConfig& config, LiveStyle& style) { return LiveRun(config, style).run(); }

}  // namespace mostyle::live
