#include "ui/model/live_source.h"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <filesystem>
#include <mutex>
#include <thread>

#include "engine/base/error.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/live/axis_stream.h"
#include "engine/live/bvh_recorder.h"
#include "engine/kinematics/kinematics.h"
#include "engine/live/bvh_recorder.h"
#include "engine/live/stream_styler.h"
#include "ui/model/lanes.h"
#include "ui/model/result_view.h"

namespace mostyle::ui {
namespace {

using Clock = std::chrono::steady_clock;
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The last `capacity` frames of a stream, as it came and styled, with where every joint was and
// when each frame was styled: a ring, so that memory stays bounded however long it runs.
class FrameRing {
 public:
  void reset(int capacity, int channels, int coordinates) {
    capacity_ = std::max(capacity, 1);
    input_.resize(capacity_, channels);
    styled_.resize(capacity_, channels);
    input_at_.resize(capacity_, coordinates);
    styled_at_.resize(capacity_, coordinates);
    times_.assign(static_cast<size_t>(capacity_), Clock::time_point());
    latency_us_.assign(static_cast<size_t>(capacity_), 0.0);
    next_ = 0;
    count_ = 0;
    total_ = 0;
  }

  // The row the next frame goes into (the oldest, once full).
  int push() {
    const int row = next_;
    next_ = (next_ + 1) % capacity_;
    count_ = std::min(count_ + 1, capacity_);
    ++total_;
    return row;
  }

  // Row k of the window, oldest first.
  int row(int k) const { return (next_ - count_ + k + capacity_) % capacity_; }
  int count() const { return count_; }
  long long total() const { return total_; }

  RowMatrix input_, styled_, input_at_, styled_at_;  // capacity x channels, capacity x 3*joints
  std::vector<Clock::time_point> times_;             // when each frame was styled
  std::vector<double> latency_us_;                   // its bytes read to it styled

 private:
  int capacity_ = 1, next_ = 0, count_ = 0;
  long long total_ = 0;
};

}  // namespace

std::string input_recording_path(const std::string& styled_path) {
  std::filesystem::path p(styled_path);
  const std::string extension = p.has_extension() ? p.extension().string() : std::string(".bvh");
  p.replace_extension();
  return p.string() + ".input" + extension;
}

std::string live_status_line(const LiveStatus& s) {
  const std::string skipped = s.skipped > 0 ? ", " + std::to_string(s.skipped) + " skipped" : std::string();
  switch (s.state) {
    case LiveState::kOff:
      return s.styled > 0 ? "disconnected after " + std::to_string(s.styled) + " frames" : "not connected";
    case LiveState::kPreparing:
      return "preparing the styles for " + s.source;
    case LiveState::kConnecting:
      return "connecting to " + s.source;
    case LiveState::kStreaming: {
      const std::string restyling = s.restyling ? ", restyling with the new takes" : std::string();
      if (s.styled == 0) return "connected to " + s.source + ", waiting for frames" + skipped + restyling;
      return "styled " + std::to_string(s.styled) + " frames, " + (s.in_cycle ? "in cycle" : "not walking") + skipped +
             restyling;
    }
    case LiveState::kClosed:
      return "source closed after " + std::to_string(s.styled) + " frames" + skipped;
    case LiveState::kFailed:
      return s.error;
  }
  return std::string();
}

// One connection: its worker thread, its builder thread (new takes made into a styler) and what
// they share with the UI thread. Each spec asked is a generation: 0 the one connect() is given,
// then one more for each set_style with other takes; strengths belong to a generation and are
// handed only to the styler made from it. The stream's lines come back to the worker from the
// engine's loop (StreamStyler) as the Sink's calls.
struct LiveSource::Run : StreamStyler::Sink {
  // Set before the threads start; read-only then.
  LiveSettings settings;
  LiveStyleSpec spec;
  double window_seconds = kLiveWindowSeconds;
  std::unique_ptr<FrameSource> source;
  std::atomic<bool> stopping{false};
  std::thread thread, builder;
  std::atomic<bool> worker_done{false}, builder_done{false};

  // Shared with the UI thread, under `mutex`.
  std::mutex mutex;
  std::condition_variable wake;  // the builder waits on it for new takes, the skeleton, or the end
  LiveStatus status;
  std::uint64_t version = 1;  // changes with the status or the window
  Skeleton skeleton;          // the stream's, once read
  double frame_time = 0.0;    // 0: not read yet
  double fps = 0.0;           // the skeleton file's rate; 0: not read yet
  FrameRing ring;
  std::vector<double> strengths;
  std::uint64_t strengths_generation = 0;  // the spec `strengths` are for
  bool strengths_waiting = false;
  LiveStyleSpec wanted;                    // the takes set last (set_style)
  std::uint64_t wanted_generation = 0;     // theirs
  std::uint64_t built_for = 0;             // the last generation the builder finished with
  std::unique_ptr<LiveStyle> built;        // made, not yet taken up by the worker
  std::uint64_t built_generation = 0;
  long long built_through = 0;             // the stream frames fed to `built` (0 .. built_through - 1)
  std::unique_ptr<BvhRecorder> record, record_input;

  // The worker's own (the ring too: it alone writes it, under the lock).
  std::unique_ptr<LiveStyle> style;
  std::uint64_t style_generation = 0;  // the spec `style` was made from
  std::vector<double> caught_up;  // a styler made meanwhile styles the frames it missed here (not shown)
  Pose input_pose, styled_pose;   // the frame's, as it came and styled
  Clock::time_point arrival;      // when the bytes being styled were read

  bool finished() const { return worker_done && builder_done; }

  void work() {
    try {
      prepare();
      if (!stopping) connect();
      if (!stopping) stream();
      end(stopping ? LiveState::kOff : LiveState::kClosed, std::string());
    } catch (const std::exception& e) {  // InputError and the rest alike: one sentence, shown
      end(stopping ? LiveState::kOff : LiveState::kFailed, e.what());
    }
    {
      std::lock_guard<std::mutex> lock(mutex);
      worker_done = true;
    }
    wake.notify_all();
  }

  // Wakes the builder to see `stopping` (set outside the lock): locking first means it is either
  // not yet waiting, and sees it, or waiting, and is woken.
  void wake_builder() {
    { std::lock_guard<std::mutex> lock(mutex); }
    wake.notify_all();
  }

  // The builder's thread: each generation of takes asked (set_style), once the stream's skeleton
  // is read, made into a styler (seconds), fed the window, and left for the worker to take up.
  // Takes asked while a styler is being made replace it: the one made is dropped, the newest made.
  void build() {
    for (;;) {
      LiveStyleSpec asked;
      std::uint64_t generation = 0;
      Skeleton stream_skeleton;
      double stream_fps = 0.0;
      {
        std::unique_lock<std::mutex> lock(mutex);
        wake.wait(lock, [this] { return stopping || worker_done || (built_for != wanted_generation && fps > 0.0); });
        if (stopping || worker_done) break;
        asked = wanted;
        generation = wanted_generation;
        if (strengths_generation == generation) asked.strengths = strengths;
        stream_skeleton = skeleton;
        stream_fps = fps;
        status.restyling = true;
        ++version;
      }
      std::unique_ptr<LiveStyle> made;
      long long through = 0;
      std::string error;
      try {
        made = std::make_unique<LiveStyle>(stream_skeleton, stream_fps, asked);
        through = warm_up(*made);
      } catch (const std::exception& e) {
        made.reset();
        error = e.what();
      }
      std::lock_guard<std::mutex> lock(mutex);
      if (generation != wanted_generation) continue;  // newer takes asked meanwhile
      built_for = generation;
      status.restyling = false;
      if (made) {
        built = std::move(made);
        built_generation = generation;
        built_through = through;
        status.restyle_error.clear();
      } else {
        status.restyle_error = "the new takes cannot style the stream (" + error + "); styled with the takes before";
      }
      ++version;
    }
    builder_done = true;
  }

  // The window's frames as they came, oldest first, through a styler just made, so that it takes up
  // the stream's gait (its strikes, its phase, its planted feet) where the stream is; returns the
  // number of stream frames it has seen then. Off the worker; a frame costs what style_frame does
  // (bench: BM_LiveStyleFrame_Axis59, tests/bench/live_style_bench.cpp).
  long long warm_up(LiveStyle& made) {
    RowMatrix frames;
    long long through = 0;
    {
      std::lock_guard<std::mutex> lock(mutex);
      frames.resize(ring.count(), ring.input_.cols());
      for (int k = 0; k < ring.count(); ++k) frames.row(k) = ring.input_.row(ring.row(k));
      through = ring.total();
    }
    std::vector<double> out(static_cast<size_t>(frames.cols()));
    for (Eigen::Index k = 0; k < frames.rows(); ++k) made.style_frame(frames.row(k).data(), out.data());
    return through;
  }

  // The worker, before a frame: a styler made from new takes, when there is one, fed the frames
  // that came since its window (from the ring, so that it has seen every frame the window holds)
  // and styling from this frame on.
  void take_up_style() {
    std::unique_ptr<LiveStyle> made;
    long long through = 0;
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (!built) return;
      made = std::move(built);
      through = built_through;
      style_generation = built_generation;
    }
    const long long first = ring.total() - ring.count();
    for (long long f = std::max(through, first); f < ring.total(); ++f)
      made->style_frame(ring.input_.row(ring.row(static_cast<int>(f - first))).data(), caught_up.data());
    style = std::move(made);
  }

  void set_state(LiveState state) {
    std::lock_guard<std::mutex> lock(mutex);
    status.state = state;
    ++version;
  }

  // The stream's skeleton, then the styler (the heavy part: the takes prepared at its rate).
  void prepare() {
    if (settings.skeleton.empty())
      throw InputError("no skeleton file: give a BVH file with the stream's hierarchy and channels");
    Clip clip = read_bvh_file(settings.skeleton);
    const double rate = clip.fps();
    style = std::make_unique<LiveStyle>(clip.skeleton, rate, spec);
    const int channels = clip.skeleton.channel_count;
    const int coordinates = 3 * static_cast<int>(clip.skeleton.joints.size());
    caught_up.assign(static_cast<size_t>(channels), 0.0);
    {
      std::lock_guard<std::mutex> lock(mutex);
      skeleton = std::move(clip.skeleton);
      frame_time = clip.frame_time;
      fps = rate;
      ring.reset(static_cast<int>(std::ceil(window_seconds * rate)), channels, coordinates);
      status.state = LiveState::kConnecting;
      ++version;
    }
    wake.notify_all();  // takes set while preparing can be made now
  }

  void connect() {
    source->open();
    set_state(LiveState::kStreaming);
  }

  // Reads until the source closes or the run is stopped, each complete line handled as it comes.
  void stream() {
    StreamStyler lines(skeleton.channel_count);
    std::string bytes;
    while (!stopping && source->read(&bytes)) {
      arrival = Clock::now();
      lines.feed(bytes, *this);
    }
    if (!stopping) lines.end(*this);
  }

  // Before each frame: the styler made from new takes, if there is one, and the strengths set
  // since the last.
  LiveStyle& styler() override {
    take_up_style();
    take_strengths();
    return *style;
  }

  // One frame styled: posed, in the window, recorded.
  void styled(const AxisFrame& frame, const double* values) override {
    const Clock::time_point done = Clock::now();
    const double* in = frame.values.data();
    pose_frame(skeleton, in, &input_pose);
    pose_frame(skeleton, values, &styled_pose);
    std::lock_guard<std::mutex> lock(mutex);
    const int row = ring.push();
    const Eigen::Index c = skeleton.channel_count;
    ring.input_.row(row) = Eigen::Map<const Eigen::RowVectorXd>(in, c);
    ring.styled_.row(row) = Eigen::Map<const Eigen::RowVectorXd>(values, c);
    for (size_t j = 0; j < input_pose.positions.size(); ++j) {
      const Eigen::Index x = 3 * static_cast<Eigen::Index>(j);
      ring.input_at_.block<1, 3>(row, x) = input_pose.positions[j].transpose();
      ring.styled_at_.block<1, 3>(row, x) = styled_pose.positions[j].transpose();
    }
    ring.times_[static_cast<size_t>(row)] = done;
    ring.latency_us_[static_cast<size_t>(row)] = std::chrono::duration<double, std::micro>(done - arrival).count();
    ++status.lines;
    ++status.styled;
    status.in_cycle = style->in_cycle();
    status.phase = style->phase();
    status.strengths = style->strengths();
    record_frame(in, values);
    ++version;
  }

  // Under the lock: the recordings' next frame (a recording that cannot be written stops, both
  // files with it, said).
  void record_frame(const double* in, const double* values) {
    std::string stopped = append_or_stop(&record, values);
    if (stopped.empty()) stopped = append_or_stop(&record_input, in);
    if (stopped.empty()) {
      if (record) status.recorded = record->frames();
      return;
    }
    status.record_error = stopped;
    record.reset();
    record_input.reset();
    status.recording = false;
  }

  void take_strengths() {
    std::vector<double> asked;
    {
      std::lock_guard<std::mutex> lock(mutex);
      // Strengths for a styler still being made wait for it (their count may not be this one's).
      if (!strengths_waiting || strengths_generation != style_generation) return;
      strengths_waiting = false;
      asked = strengths;
    }
    std::string refused;
    try {
      style->set_strengths(asked);
    } catch (const InputError& e) {
      refused = e.what();
    }
    std::lock_guard<std::mutex> lock(mutex);
    status.strength_error = refused;
  }

  void skipped(long long line, const std::string& why) override {
    std::lock_guard<std::mutex> lock(mutex);
    ++status.lines;
    ++status.skipped;
    status.last_skip = "line " + std::to_string(line) + ": " + why;
    ++version;
  }

  // The recordings end complete; the state says how the stream ended.
  void end(LiveState state, const std::string& error) {
    std::lock_guard<std::mutex> lock(mutex);
    record.reset();
    record_input.reset();
    status.recording = false;
    status.restyling = false;
    status.state = state;
    status.error = error;
    ++version;
  }
};

LiveSource::LiveSource(FrameSourceMaker sources, double window_seconds)
    : sources_(std::move(sources)), window_seconds_(window_seconds) {}

LiveSource::~LiveSource() {
  disconnect();
  for (const std::shared_ptr<Run>& run : retired_) {
    run->thread.join();
    run->builder.join();
  }
}

void LiveSource::connect(const LiveSettings& settings, const LiveStyleSpec& spec) {
  disconnect();
  auto run = std::make_shared<Run>();
  run->settings = settings;
  run->spec = spec;
  run->window_seconds = window_seconds_;
  run->status.source = settings.address;
  run->status.state = LiveState::kPreparing;
  run->strengths = spec.strengths;
  run->wanted = spec;
  styled_with_ = spec.takes;
  // A fresh window: the stream shown before goes, the next is placed anew.
  status_ = run->status;
  metrics_ = LiveMetrics();
  input_.reset();
  styled_.reset();
  takes_.clear();
  placed_ = false;
  first_frame_ = 0;
  seen_version_ = 0;
  try {
    run->source = sources_(settings.address);
  } catch (const std::exception& e) {
    status_.state = LiveState::kFailed;
    status_.error = e.what();
    return;
  }
  Run* r = run.get();
  run->thread = std::thread([r] { r->work(); });
  run->builder = std::thread([r] { r->build(); });
  run_ = std::move(run);
}

void LiveSource::disconnect() {
  if (!run_) return;
  run_->stopping = true;
  run_->source->stop();
  run_->wake_builder();
  poll();  // what it had styled stays shown
  retired_.push_back(std::move(run_));
  run_.reset();
  status_.state = LiveState::kOff;
  status_.recording = false;
  status_.restyling = false;  // a styler being made is dropped with its stream
  metrics_.frames_per_s = 0.0;
}

bool LiveSource::active() const {
  return status_.state == LiveState::kPreparing || status_.state == LiveState::kConnecting ||
         status_.state == LiveState::kStreaming;
}

void LiveSource::set_strengths(const std::vector<double>& strengths) {
  if (!run_) return;
  std::lock_guard<std::mutex> lock(run_->mutex);
  if (run_->strengths == strengths) return;
  run_->strengths = strengths;  // for the takes set last (their generation's)
  run_->strengths_waiting = true;
}

void LiveSource::set_style(const LiveStyleSpec& spec) {
  if (!run_ || !active()) return;
  if (spec.takes == styled_with_) return set_strengths(spec.strengths);  // the same clips: no new styler
  {
    std::lock_guard<std::mutex> lock(run_->mutex);
    if (run_->worker_done) return;  // the stream ended since the last poll(): nothing to restyle
    styled_with_ = spec.takes;
    run_->wanted = spec;
    ++run_->wanted_generation;
    run_->strengths = spec.strengths;
    run_->strengths_generation = run_->wanted_generation;
    run_->strengths_waiting = false;  // the new styler is made with them
    run_->status.restyling = true;
    ++run_->version;
  }
  run_->wake.notify_all();
  status_.restyling = true;
}

bool LiveSource::start_recording(const std::string& path, bool with_input) {
  if (!run_) {
    status_.record_error = "Record: connect to a stream first.";
    return false;
  }
  std::lock_guard<std::mutex> lock(run_->mutex);
  Run& r = *run_;
  r.record.reset();
  r.record_input.reset();
  r.status.recording = false;
  if (r.frame_time <= 0.0 || r.status.state != LiveState::kStreaming) {
    r.status.record_error = "Record: wait until the stream is connected.";
  } else {
    try {
      auto styled = std::make_unique<BvhRecorder>(path, r.skeleton, r.frame_time);
      std::unique_ptr<BvhRecorder> input;
      if (with_input) input = std::make_unique<BvhRecorder>(input_recording_path(path), r.skeleton, r.frame_time);
      r.record = std::move(styled);
      r.record_input = std::move(input);
      r.status.recording = true;
      r.status.record_path = path;
      r.status.recorded = 0;
      r.status.record_error.clear();
    } catch (const InputError& e) {
      r.status.record_error = e.what();
    }
  }
  ++r.version;
  status_.recording = r.status.recording;
  status_.record_error = r.status.record_error;
  return r.status.recording;
}

void LiveSource::stop_recording() {
  if (!run_) return;
  std::lock_guard<std::mutex> lock(run_->mutex);
  run_->record.reset();  // the last line ended: the file is complete
  run_->record_input.reset();
  run_->status.recording = false;
  ++run_->version;
  status_.recording = false;
}

bool LiveSource::poll() {
  // Workers that were stopped and have finished are done with.
  for (auto it = retired_.begin(); it != retired_.end();) {
    if ((*it)->finished()) {
      (*it)->thread.join();
      (*it)->builder.join();
      it = retired_.erase(it);
    } else {
      ++it;
    }
  }
  if (!run_) return false;
  bool changed = false;
  {
    std::lock_guard<std::mutex> lock(run_->mutex);
    if (run_->version != seen_version_) {
      seen_version_ = run_->version;
      changed = run_->ring.total() != first_frame_ + (input_ ? input_->frames() : 0);
      status_ = run_->status;
      if (changed) take_up_window(*run_);
    }
  }
  // The rate and the latency over the last seconds, also when no frame comes.
  const Clock::time_point now = Clock::now();
  const FrameRing& ring = run_->ring;  // its times: only the worker writes them, under the lock
  std::vector<double> recent;
  {
    std::lock_guard<std::mutex> lock(run_->mutex);
    const auto since = now - std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kLiveMetricsSeconds));
    Clock::time_point first = now;
    for (int k = ring.count() - 1; k >= 0; --k) {
      const size_t row = static_cast<size_t>(ring.row(k));
      if (ring.times_[row] < since) break;
      recent.push_back(ring.latency_us_[row]);
      first = ring.times_[row];
    }
    const double span = std::chrono::duration<double>(now - first).count();
    metrics_.frames_per_s = recent.size() > 1 && span > 0.0 ? static_cast<double>(recent.size()) / std::max(span, 1e-3) : 0.0;
  }
  metrics_.skipped = status_.skipped;
  if (recent.empty()) {
    metrics_.latency_mean_us = metrics_.latency_p99_us = -1.0;
  } else {
    double sum = 0.0;
    for (double v : recent) sum += v;
    metrics_.latency_mean_us = sum / static_cast<double>(recent.size());
    const size_t at = std::min(recent.size() - 1, static_cast<size_t>(std::ceil(0.99 * static_cast<double>(recent.size()))) - 1);
    std::nth_element(recent.begin(), recent.begin() + static_cast<std::ptrdiff_t>(at), recent.end());
    metrics_.latency_p99_us = recent[at];
  }
  return changed;
}

// Under the run's lock: the window as two clips and their joints' positions, oldest first.
void LiveSource::take_up_window(Run& run) {
  const FrameRing& ring = run.ring;
  const int n = ring.count();
  auto input = std::make_shared<Clip>();
  input->source = run.settings.address;
  input->skeleton = run.skeleton;
  input->frame_time = run.frame_time;
  input->motion.resize(n, ring.input_.cols());
  auto styled = std::make_shared<Clip>(*input);
  styled->source = run.settings.address + " (styled)";
  input_positions_.resize(n, ring.input_at_.cols());
  styled_positions_.resize(n, ring.styled_at_.cols());
  for (int k = 0; k < n; ++k) {
    const int row = ring.row(k);
    input->motion.row(k) = ring.input_.row(row);
    styled->motion.row(k) = ring.styled_.row(row);
    input_positions_.row(k) = ring.input_at_.row(row);
    styled_positions_.row(k) = ring.styled_at_.row(row);
  }
  first_frame_ = ring.total() - n;
  input_ = std::move(input);
  styled_ = std::move(styled);
  make_takes();
}

// The stream and the styled stream as the viewport's takes: on the stream's floor, its first
// body centre at the origin, the styled one beside it (placed once per stream, so that the
// skeletons walk on).
void LiveSource::make_takes() {
  if (!input_ || input_->frames() == 0) return;
  if (!placed_) {
    const Placement placed = placement_of(input_positions_);
    shift_ = placed.shift;
    side_ = placed.side;
    size_ = placed.size;
    spacing_ = placed.spacing;
    placed_ = true;
  }
  std::vector<int> parents;
  for (const Joint& j : input_->skeleton.joints) parents.push_back(j.parent);
  auto placed = [this](Eigen::MatrixXd positions, const Eigen::Vector3d& offset) {
    for (Eigen::Index j = 0; 3 * j < positions.cols(); ++j)
      for (int a = 0; a < 3; ++a) positions.col(3 * j + a).array() += offset[a];
    return positions;
  };
  takes_.clear();
  takes_.push_back(shown_take("stream  " + input_->source, take_color(0), input_, input_->fps(), parents,
                              placed(input_positions_, shift_)));
  takes_.push_back(shown_take("styled", result_color(), styled_, styled_->fps(), parents,
                              placed(styled_positions_, shift_ + static_cast<double>(spacing_) * side_)));
  for (ShownMotion& t : takes_) {
    t.path = input_->source;
    t.size = size_;
  }
}

void LiveSource::move_takes_into(std::vector<ShownMotion>* shown) {
  if (takes_.empty()) return;
  for (size_t i = 0; i < shown->size() && i < takes_.size(); ++i) takes_[i].visible = (*shown)[i].visible;
  *shown = std::move(takes_);
  takes_.clear();
}

bool LiveSource::wait_until(const std::function<bool(const LiveStatus&)>& done, std::chrono::milliseconds timeout) {
  const Clock::time_point until = Clock::now() + timeout;
  for (;;) {
    poll();
    if (done(status_)) return true;
    if (Clock::now() >= until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

}  // namespace mostyle::ui
