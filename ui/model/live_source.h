#pragma once
// The editor's Live source: a motion-capture stream in Axis Neuron's "BVH broadcasting" string
// format (engine/live/axis_stream.h) styled frame by frame as it arrives, as `mostyle-cli live`
// styles it (engine/live/live_style.h), with the takes loaded in the editor as the neutral and
// the styles (ui/model/live_style_spec.h says which is which in each mode). The viewport shows the stream and the styled stream side by side at the newest
// frame; the Files panel connects and records, the Metrics panel shows the latency.
//
// Threads: connect() starts one worker thread of its own, which reads the stream's skeleton,
// prepares the styler (heavy: seconds), opens the FrameSource, then reads its bytes and hands
// them to the engine's stream loop (engine/live/stream_styler.h: lines cut, parsed, styled, as
// the command line's live does), recording each frame styled and appending it to a window of
// the last window_seconds. The styler is the worker's alone: strengths set from the UI thread are handed
// to it under a lock and applied before its next frame. New takes (set_style) are made into a
// new styler on a second thread of the connection's, which hands it to the worker when made;
// the worker styles with the one it has meanwhile and keeps the connection. The UI thread calls the public
// functions; poll() takes up the newest window as two Clips and two takes for the viewport
// (copies: the worker never waits for the UI). Memory is bounded however long it runs: the
// window, a line, the styler's.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "engine/base/clip.h"
#include "engine/live/live_style.h"
#include "ui/model/editor_state.h"

namespace mostyle::ui {

// Where a stream's bytes come from: a TCP connection (the app's), a fake in tests. Used by the
// live worker's thread only, except stop().
class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // Connects; blocks until connected, refused or stopped. Throws InputError in one sentence
  // ("cannot connect to HOST:PORT: Connection refused").
  virtual void open() = 0;
  // Waits for the stream's next bytes and puts them in *bytes (replacing what it held). false:
  // the source closed (or stop() was called). Throws InputError in one sentence on a read error.
  virtual bool read(std::string* bytes) = 0;
  // Any thread, any time: open() and read() return at once, now and later.
  virtual void stop() = 0;
};

// Makes the source for an address as typed ("HOST:PORT"); throws InputError naming the address
// when it is not one.
using FrameSourceMaker = std::function<std::unique_ptr<FrameSource>(const std::string& address)>;

// What the Files panel's Live section edits. Not in the Document: connecting is not an edit
// that undo takes back, nor part of a session.
struct LiveSettings {
  std::string address = "localhost:7001";  // HOST:PORT of the BVH broadcasting server
  // A BVH file with the stream's hierarchy and channels (exported from Axis with the same output
  // settings); its frames are ignored, its Frame Time is the stream's rate.
  std::string skeleton;
  std::string record_path = "live_styled.bvh";  // the styled stream's recording
  bool record_input = false;                    // and the stream as it came, beside it (input_recording_path)
};

// The file the stream as it came is recorded to beside the styled one: "styled.bvh" ->
// "styled.input.bvh".
std::string input_recording_path(const std::string& styled_path);

constexpr double kLiveWindowSeconds = 10.0;   // the stream kept for the viewport
constexpr double kLiveMetricsSeconds = 2.0;   // the frames the rate and the latency are over

enum class LiveState {
  kOff,         // never connected, or disconnected
  kPreparing,   // reading the skeleton, preparing the styles
  kConnecting,  // waiting for the source
  kStreaming,   // connected: frames are styled as they come
  kClosed,      // the source closed the stream
  kFailed,      // error says why
};

struct LiveStatus {
  LiveState state = LiveState::kOff;
  std::string source;       // the address connected to, as typed
  std::string error;        // kFailed: one sentence
  long long lines = 0;      // lines read: frames and lines that are not
  long long styled = 0;     // frames styled
  long long skipped = 0;    // lines that are not frames (malformed, too long, another avatar's): counted, skipped
  std::string last_skip;    // why the last one was skipped: "line 12: expected 96 values ..., found 95"
  bool restyling = false;   // new takes are being made into a styler; the stream is styled with the one before until made
  std::string restyle_error;  // why the takes set last could not style the stream (it is styled as before), or ""
  bool in_cycle = false;    // the styler's, on the last frame (LiveStyle::in_cycle)
  double phase = 0.0;       // [0, 1) within the neutral's gait cycle
  std::vector<double> strengths;  // as eased on the last frame, one per style
  std::string strength_error;     // why the strengths last set were refused, or ""
  bool recording = false;
  std::string record_path;  // the styled recording's file
  long long recorded = 0;   // frames in it
  std::string record_error; // why the last recording stopped or did not start, one sentence
};

struct LiveMetrics {
  double frames_per_s = 0.0;      // frames styled per second over the last kLiveMetricsSeconds
  double latency_mean_us = -1.0;  // a frame's bytes read to the frame styled, over the same frames; -1: none
  double latency_p99_us = -1.0;   // its 99th percentile
  long long skipped = 0;          // LiveStatus::skipped
};

// The status in one line for the Files panel: "preparing the styles", "connecting to HOST:PORT",
// "styled 1200 frames, in cycle" (", 3 skipped", ", restyling with the new takes"), "source closed
// after 1200 frames", the error.
std::string live_status_line(const LiveStatus& status);

class LiveSource {
 public:
  // sources: how connect() makes a source for an address. window_seconds: how much of the
  // stream poll() shows (at the skeleton's rate).
  explicit LiveSource(FrameSourceMaker sources, double window_seconds = kLiveWindowSeconds);
  ~LiveSource();  // disconnects, waits for the worker
  LiveSource(const LiveSource&) = delete;
  LiveSource& operator=(const LiveSource&) = delete;

  // Starts styling the stream at settings.address with spec's takes ([neutral, styles...]) and
  // strengths, on a new worker thread; a stream before is disconnected. Never blocks: a bad
  // address, skeleton or take, or a refused connection shows as status() kFailed with its
  // sentence (after a later poll() for what the worker finds).
  void connect(const LiveSettings& settings, const LiveStyleSpec& spec);
  // Stops the stream (the recording ends, complete); the window shown stays. Never blocks: the
  // worker finishes on its own (a styler being prepared first finishes preparing).
  void disconnect();
  // Preparing, connecting or streaming.
  bool active() const;
  // What the Files panel's Live section edits and connect() is given (UI thread).
  LiveSettings& settings() { return settings_; }

  // One per style, each in [-1, 2]; handed to the worker, which eases to them from its next
  // frame (LiveStyle::set_strengths). Strengths the styler refuses (a wrong count, a value out
  // of range) change nothing and are said in status().strength_error.
  void set_strengths(const std::vector<double>& strengths);

  // The takes and strengths to style with from now on, for the editor to call every frame while
  // active(). The same takes as the spec asked last (the same clips, in the same order): only the
  // strengths are handed on (set_strengths). Other takes (reloaded, another mode or neutral): a
  // new styler is made off this thread and the worker's, the connection kept and the stream
  // styled with the styler before meanwhile (status().restyling, until it is made); from the next
  // frame on the new one styles, first fed every frame the window holds so that it takes up the
  // stream's gait where it is. New takes that cannot style the stream leave the styler as it was and say why
  // in status().restyle_error. Not connected: nothing. O(takes) when the takes are the same.
  void set_style(const LiveStyleSpec& spec);

  // Records the styled stream to `path` (and the stream as it came, to input_recording_path,
  // when with_input), from the next frame on: a BVH file that reads whole at every moment
  // (engine/live/bvh_recorder.h). false when not streaming yet or the file cannot be written
  // (status().record_error says why). A recording before ends first.
  bool start_recording(const std::string& path, bool with_input);
  void stop_recording();

  // UI thread, once a frame: takes up the worker's status, the window and the metrics. true
  // when the window changed (new frames).
  bool poll();
  const LiveStatus& status() const { return status_; }
  const LiveMetrics& metrics() const { return metrics_; }
  // The last window_seconds of the stream as it came and as styled (frames x channels, the
  // skeleton's); null before the first frame. Frame k of both is the same stream frame.
  const std::shared_ptr<const Clip>& input() const { return input_; }
  const std::shared_ptr<const Clip>& styled() const { return styled_; }
  // The stream's frame number (from 0 at connect) of the window's first frame.
  long long window_first_frame() const { return first_frame_; }
  // The viewport's two takes for the window (EditorState::takes while live: the stream at 0,
  // the styled stream 1, as ResultView lays out a take and its result): every joint's position
  // on the stream's floor, the styled stream beside it. Empty before the first frame.
  const std::vector<ShownMotion>& takes() const { return takes_; }
  // Whether there is a window to show (a frame styled since connect()).
  bool has_window() const { return input_ != nullptr && input_->frames() > 0; }
  // Moves takes() into *shown (the editor's EditorState::takes), each keeping the `visible` it
  // had there; takes() is empty until the next window. No copy of the positions.
  void move_takes_into(std::vector<ShownMotion>* shown);

  // Blocks until `done` holds for status() (polling), or `timeout` passes; returns whether it
  // held. Tests and screenshots only.
  bool wait_until(const std::function<bool(const LiveStatus&)>& done, std::chrono::milliseconds timeout);

 private:
  struct Run;
  void take_up_window(Run& run);
  void make_takes();

  FrameSourceMaker sources_;
  double window_seconds_;
  LiveSettings settings_;
  std::shared_ptr<Run> run_;                    // the stream connected last
  std::vector<std::shared_ptr<const Clip>> styled_with_;  // the takes of the spec set last (connect, set_style)
  std::vector<std::shared_ptr<Run>> retired_;   // disconnected, their workers finishing
  std::uint64_t seen_version_ = 0;
  LiveStatus status_;
  LiveMetrics metrics_;
  std::shared_ptr<const Clip> input_, styled_;
  Eigen::MatrixXd input_positions_, styled_positions_;  // frames x 3*joints, file units
  long long first_frame_ = 0;
  bool placed_ = false;          // the placement is fixed at the first window of a stream
  Eigen::Vector3d shift_ = Eigen::Vector3d::Zero(), side_ = Eigen::Vector3d::UnitX();
  float size_ = 1.0f, spacing_ = 1.0f;
  std::vector<ShownMotion> takes_;
};

}  // namespace mostyle::ui
