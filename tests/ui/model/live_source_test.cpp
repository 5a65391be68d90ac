// The editor's live source (ui/model/live_source.h) over a fake FrameSource that feeds the lines
// of a bundled take as Axis Neuron sends them: every frame is styled as the styler styles it
// alone, the strengths set reach the styler, the window stays bounded, bad lines are counted and
// skipped, the source closing is said, a recording reads back as BVH with its frames, and new
// takes restyle the stream on the same connection.
#include <condition_variable>
#include <deque>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <unistd.h>

#include <catch2/catch.hpp>

#include "engine/base/error.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/live/axis_stream.h"
#include "tests/test_data.h"
#include "ui/model/live_source.h"
#include "ui/model/live_style_spec.h"
#include "ui/model/result_view.h"

using namespace mostyle;
using namespace mostyle::ui;
namespace fs = std::filesystem;

namespace {

constexpr auto kPatience = std::chrono::seconds(120);  // a bound on waiting, never a measure

// Bytes a test hands over, read by the live worker as a connection's.
struct FakeStream {
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::string> chunks;
  bool closed = false, stopped = false;

  void send(const std::string& bytes) {
    std::lock_guard<std::mutex> lock(mutex);
    chunks.push_back(bytes);
    changed.notify_all();
  }
  void close() {
    std::lock_guard<std::mutex> lock(mutex);
    closed = true;
    changed.notify_all();
  }
};

class FakeSource : public FrameSource {
 public:
  explicit FakeSource(std::shared_ptr<FakeStream> stream) : stream_(std::move(stream)) {}
  void open() override {}
  bool read(std::string* bytes) override {
    std::unique_lock<std::mutex> lock(stream_->mutex);
    stream_->changed.wait(lock, [this] { return stream_->stopped || stream_->closed || !stream_->chunks.empty(); });
    if (stream_->stopped || stream_->chunks.empty()) return false;
    *bytes = std::move(stream_->chunks.front());
    stream_->chunks.pop_front();
    return true;
  }
  void stop() override {
    std::lock_guard<std::mutex> lock(stream_->mutex);
    stream_->stopped = true;
    stream_->changed.notify_all();
  }

 private:
  std::shared_ptr<FakeStream> stream_;
};

std::shared_ptr<const Clip> load(const std::string& name) {
  return std::make_shared<const Clip>(read_bvh_file(test::asset("motions/" + name)));
}

const std::string kStream = "cmu142_walk_clumsy.bvh";

// The stream's frames as Axis Neuron's lines (values with 7 significant digits).
struct StreamLines {
  std::shared_ptr<const Clip> clip = load(kStream);
  std::string line(int frame) const {
    std::string out;
    append_axis_line(&out, 0, "Avatar00", nullptr, 0, clip->motion.row(frame).data(), clip->skeleton.channel_count);
    return out;
  }
  std::string lines(int from, int to) const {  // frames [from, to)
    std::string out;
    for (int f = from; f < to; ++f) out += line(f);
    return out;
  }
};

// The happy walk the neutral, the marching (and the joyful) walk the styles.
LiveStyleSpec spec(std::vector<double> strengths) {
  LiveStyleSpec s;
  s.takes = {load("cmu142_walk_happy.bvh"), load("cmu142_walk_marching.bvh")};
  if (strengths.size() > 1) s.takes.push_back(load("cmu142_walk_joy.bvh"));
  s.strengths = std::move(strengths);
  return s;
}

struct Live {
  std::shared_ptr<FakeStream> stream = std::make_shared<FakeStream>();
  LiveSource live;
  explicit Live(double window_seconds = kLiveWindowSeconds)
      : live([this](const std::string&) { return std::make_unique<FakeSource>(stream); }, window_seconds) {}

  void connect(std::vector<double> strengths = {1.0}) { connect(spec(std::move(strengths))); }
  void connect(const LiveStyleSpec& with) {
    LiveSettings settings;
    settings.address = "fake:1";
    settings.skeleton = test::asset("motions/" + kStream);
    live.connect(settings, with);
    REQUIRE(live.wait_until([](const LiveStatus& s) { return s.state != LiveState::kPreparing; }, kPatience));
    REQUIRE(live.wait_until([](const LiveStatus& s) { return s.state != LiveState::kConnecting; }, kPatience));
    REQUIRE(live.status().state == LiveState::kStreaming);
  }
  // Waits until `lines` lines have been read (styled or skipped).
  void wait_lines(long long lines) {
    REQUIRE(live.wait_until([lines](const LiveStatus& s) { return s.lines >= lines; }, kPatience));
  }
};

// A scratch folder for this process.
struct Scratch {
  fs::path dir = fs::temp_directory_path() / ("mostyle_live_source_test_" + std::to_string(::getpid()));
  Scratch() { fs::create_directories(dir); }
  ~Scratch() { fs::remove_all(dir); }
};

}  // namespace

TEST_CASE("live source: every frame is styled as the styler alone styles it, and the window stays bounded") {
  const StreamLines lines;
  Live l(/*window_seconds=*/1.0);  // 120 frames of the 120 fps stream
  l.connect();
  const int frames = 300;
  l.stream->send(lines.lines(0, 100));
  l.stream->send(lines.lines(100, frames));
  l.wait_lines(frames);
  l.live.poll();
  const LiveStatus& s = l.live.status();
  CHECK(s.styled == frames);
  CHECK(s.skipped == 0);
  CHECK(s.state == LiveState::kStreaming);
  CHECK(live_status_line(s).rfind("styled 300 frames, ", 0) == 0);

  // The last second only: the memory held does not grow with the stream.
  REQUIRE(l.live.input() != nullptr);
  REQUIRE(l.live.styled() != nullptr);
  CHECK(l.live.input()->frames() == 120);
  CHECK(l.live.styled()->frames() == 120);
  CHECK(l.live.window_first_frame() == frames - 120);

  // The same styler fed the same lines gives the same frames, bit for bit.
  LiveStyle alone(lines.clip->skeleton, lines.clip->fps(), spec({1.0}));
  const int channels = lines.clip->skeleton.channel_count;
  AxisFrame frame;
  std::string reason;
  std::vector<double> out(static_cast<size_t>(channels));
  double most = 0.0, moved = 0.0;
  for (int f = 0; f < frames; ++f) {
    REQUIRE(parse_axis_line(lines.line(f).substr(0, lines.line(f).size() - 1), channels, &frame, &reason) == AxisLineStatus::kOk);
    alone.style_frame(frame.values.data(), out.data());
    const int k = f - (frames - 120);
    if (k < 0) continue;
    for (int c = 0; c < channels; ++c) {
      most = std::max(most, std::abs(l.live.styled()->motion(k, c) - out[static_cast<size_t>(c)]));
      moved = std::max(moved, std::abs(l.live.styled()->motion(k, c) - l.live.input()->motion(k, c)));
      REQUIRE(l.live.input()->motion(k, c) == frame.values[static_cast<size_t>(c)]);
    }
  }
  CHECK(most == 0.0);
  CHECK(moved > 1.0);  // degrees or file units: the style changed the stream

  // The viewport's two takes: the stream, then the styled stream in the result's colour.
  const std::vector<ShownMotion>& takes = l.live.takes();
  REQUIRE(takes.size() == 2);
  CHECK(takes[0].ok());
  CHECK(takes[1].ok());
  CHECK(takes[0].frames() == 120);
  CHECK(takes[1].frames() == 120);
  CHECK(takes[0].color == take_color(0));
  CHECK(takes[1].color == result_color());
  CHECK(takes[0].label.find("stream") != std::string::npos);
  CHECK(takes[0].parents.size() == lines.clip->skeleton.joints.size());
  CHECK(takes[0].positions.cols() == 3 * static_cast<Eigen::Index>(lines.clip->skeleton.joints.size()));

  // The metrics of the frames just styled.
  CHECK(l.live.metrics().latency_mean_us >= 0.0);
  CHECK(l.live.metrics().latency_p99_us >= 0.0);
  CHECK(l.live.metrics().skipped == 0);
}

TEST_CASE("live source: strengths set from the editor reach the styler; refused ones are said") {
  const StreamLines lines;
  Live l;
  l.connect({1.0, 0.5});
  l.stream->send(lines.lines(0, 30));
  l.wait_lines(30);
  CHECK(l.live.status().strengths == std::vector<double>{1.0, 0.5});
  // Eased over half a second: 60 frames of the stream.
  l.live.set_strengths({0.0, 2.0});
  l.stream->send(lines.lines(30, 130));
  l.wait_lines(130);
  CHECK(l.live.status().strengths == std::vector<double>{0.0, 2.0});
  CHECK(l.live.status().strength_error.empty());
  // Out of range: nothing changes, and the status says why.
  l.live.set_strengths({0.0, 3.0});
  l.stream->send(lines.lines(130, 140));
  l.wait_lines(140);
  CHECK(l.live.status().strengths == std::vector<double>{0.0, 2.0});
  CHECK(!l.live.status().strength_error.empty());
  CHECK(l.live.status().styled == 140);
}

TEST_CASE("live source: a malformed line is counted and skipped, and the source closing is said") {
  const StreamLines lines;
  Live l;
  l.connect();
  l.stream->send(lines.lines(0, 10));
  l.stream->send("0 Avatar00 1 2 3 ||\n");         // line 11: too few values
  l.stream->send("0 Avatar00 garbage here\n");     // line 12: no "||"
  l.stream->send(lines.lines(10, 20));
  l.wait_lines(22);
  l.live.poll();
  CHECK(l.live.status().styled == 20);
  CHECK(l.live.status().skipped == 2);
  CHECK(l.live.status().last_skip.rfind("line 12: ", 0) == 0);
  CHECK(l.live.metrics().skipped == 2);
  CHECK(live_status_line(l.live.status()).find(", 2 skipped") != std::string::npos);
  // The stream ends: the status says the source closed, what was styled stays shown.
  l.stream->close();
  REQUIRE(l.live.wait_until([](const LiveStatus& s) { return s.state == LiveState::kClosed; }, kPatience));
  CHECK(!l.live.active());
  CHECK(live_status_line(l.live.status()).rfind("source closed", 0) == 0);
  CHECK(l.live.input()->frames() == 20);
  CHECK(l.live.takes().size() == 2);
}

TEST_CASE("live source: a recording of the styled stream (and the input) reads as BVH with its frames") {
  const StreamLines lines;
  Scratch scratch;
  const std::string path = (scratch.dir / "styled.bvh").string();
  Live l;
  l.connect();
  // Not streaming yet: nothing to record.
  LiveSource idle([](const std::string&) -> std::unique_ptr<FrameSource> { return nullptr; });
  CHECK_FALSE(idle.start_recording(path, false));
  CHECK(!idle.status().record_error.empty());

  l.stream->send(lines.lines(0, 20));
  l.wait_lines(20);
  REQUIRE(l.live.start_recording(path, /*with_input=*/true));
  l.stream->send(lines.lines(20, 50));
  l.wait_lines(50);
  l.live.poll();
  CHECK(l.live.status().recording);
  CHECK(l.live.status().recorded == 30);
  // Whole at every moment: read while it is being written.
  CHECK(read_bvh_file(path).frames() == 30);
  l.live.stop_recording();
  l.stream->send(lines.lines(50, 60));
  l.wait_lines(60);
  const Clip styled = read_bvh_file(path);
  const Clip input = read_bvh_file(input_recording_path(path));
  CHECK(input_recording_path(path) == (scratch.dir / "styled.input.bvh").string());
  REQUIRE(styled.frames() == 30);
  REQUIRE(input.frames() == 30);
  CHECK(styled.skeleton.channel_count == lines.clip->skeleton.channel_count);
  // Frames 20 to 49 of the window, as styled and as they came.
  l.live.poll();
  const Clip& window = *l.live.styled();
  REQUIRE(l.live.window_first_frame() == 0);
  for (int f = 0; f < 30; ++f)
    for (int c = 0; c < styled.skeleton.channel_count; ++c) {
      REQUIRE(std::abs(styled.motion(f, c) - window.motion(20 + f, c)) <= 1e-6 * std::max(1.0, std::abs(window.motion(20 + f, c))));
      REQUIRE(std::abs(input.motion(f, c) - l.live.input()->motion(20 + f, c)) <= 1e-6 * std::max(1.0, std::abs(input.motion(f, c))));
    }
  // A folder that does not exist: said in one sentence, no recording.
  CHECK_FALSE(l.live.start_recording((scratch.dir / "absent" / "x.bvh").string(), false));
  CHECK(l.live.status().record_error.find("absent") != std::string::npos);
}

TEST_CASE("live source: a bad address, a missing skeleton and too few takes are one sentence each") {
  LiveSource refusing([](const std::string& address) -> std::unique_ptr<FrameSource> {
    throw InputError("Live: '" + address + "' is not HOST:PORT");
  });
  LiveSettings settings;
  settings.address = "nowhere";
  settings.skeleton = test::asset("motions/" + kStream);
  refusing.connect(settings, spec({1.0}));
  CHECK(refusing.status().state == LiveState::kFailed);
  CHECK(live_status_line(refusing.status()) == "Live: 'nowhere' is not HOST:PORT");

  Live l;
  settings.address = "fake:1";
  settings.skeleton = "/nonexistent/skeleton.bvh";
  l.live.connect(settings, spec({1.0}));
  REQUIRE(l.live.wait_until([](const LiveStatus& s) { return s.state == LiveState::kFailed; }, kPatience));
  CHECK(l.live.status().error.find("skeleton.bvh") != std::string::npos);
  CHECK(!l.live.active());
}

TEST_CASE("live style plan: one rule, every take but the neutral a style at its layer's weight") {
  Document d;
  CHECK(live_style_plan(d, 1).takes.empty());  // nothing to style with
  CHECK(live_style_plan(d, 1).strengths.empty());

  // A pair: A the neutral, B the style, at alpha; in transfer mode too (A its own neutral).
  set_pair_alpha(d, 0.25);
  CHECK(live_style_plan(d, 2).takes == std::vector<int>{0, 1});
  CHECK(live_strengths(d, 2) == std::vector<double>{0.25});
  d.controls.transfer = true;
  CHECK(live_style_plan(d, 2).takes == std::vector<int>{0, 1});
  CHECK(live_strengths(d, 2) == std::vector<double>{0.25});
  d.controls.transfer = false;

  // A mix: the stream stands in for take 0, the others' weights are their strengths.
  set_layer_weights(d, {0.5, 0.25, 0.25});
  CHECK(live_style_plan(d, 3).takes == std::vector<int>{0, 1, 2});
  CHECK(live_strengths(d, 3) == std::vector<double>{0.25, 0.25});
  set_layer_weights(d, {-0.5, 0.25, 1.25});
  CHECK(live_strengths(d, 3) == std::vector<double>{0.25, 1.25});
  // Layers not one per take (takes just changed): equal weights, as the mix takes them.
  set_layer_weights(d, {0.5, 0.5});
  CHECK(live_strengths(d, 4) == std::vector<double>{0.25, 0.25, 0.25});

  // A transfer: the stream stands in for the content (take 0), take `neutral` is the neutral,
  // every other take a style at its layer's weight (its strength), clamped to [-1, 2].
  d.controls.transfer = true;
  d.controls.neutral = 2;
  set_layer_weights(d, {1.0, 0.5, 0.9, 3.0});
  CHECK(live_style_plan(d, 4).takes == std::vector<int>{2, 1, 3});
  CHECK(live_strengths(d, 4) == std::vector<double>{0.5, 2.0});
  set_layer_weights(d, {1.0, -4.0, 0.9, 0.0});
  CHECK(live_strengths(d, 4) == std::vector<double>{-1.0, 0.0});
  // A neutral beyond the takes is the last one, as the transfer takes it.
  d.controls.neutral = 7;
  CHECK(live_style_plan(d, 4).takes == std::vector<int>{3, 1, 2});
  CHECK(live_strengths(d, 4) == std::vector<double>{-1.0, 0.9});
  // The content its own neutral: the content take is the neutral, every other take a style.
  d.controls.content_neutral = true;
  CHECK(live_style_plan(d, 4).takes == std::vector<int>{0, 1, 2, 3});
  CHECK(live_strengths(d, 4) == std::vector<double>{-1.0, 0.9, 0.0});

  // The spec: the loaded takes' clips in the plan's order, shared.
  PreparedTakes prepared;
  for (int i = 0; i < 4; ++i) {
    PreparedTake take;
    auto clip = std::make_shared<Clip>();
    clip->source = "take" + std::to_string(i);
    take.clip = clip;
    prepared.takes.push_back(std::move(take));
  }
  d.controls.content_neutral = false;
  d.controls.neutral = 3;
  const LiveStyleSpec s = live_style_spec(prepared, d);
  REQUIRE(s.takes.size() == 3);
  CHECK(s.takes[0] == prepared.takes[3].clip);
  CHECK(s.takes[1] == prepared.takes[1].clip);
  CHECK(s.takes[2] == prepared.takes[2].clip);
  CHECK(s.strengths == std::vector<double>{-1.0, 0.9});
  prepared.takes.resize(1);
  CHECK_THROWS_AS(live_style_spec(prepared, d), InputError);
}

namespace {

// The stream's frames [from, to) through `style`, each frame's output a row (frames x channels).
Eigen::MatrixXd styled_alone(LiveStyle& style, const StreamLines& lines, int from, int to) {
  const int channels = lines.clip->skeleton.channel_count;
  Eigen::MatrixXd out(to - from, channels);
  AxisFrame frame;
  std::string reason;
  std::vector<double> row(static_cast<size_t>(channels));
  for (int f = from; f < to; ++f) {
    const std::string line = lines.line(f);
    REQUIRE(parse_axis_line(line.substr(0, line.size() - 1), channels, &frame, &reason) == AxisLineStatus::kOk);
    style.style_frame(frame.values.data(), row.data());
    out.row(f - from) = Eigen::Map<const Eigen::RowVectorXd>(row.data(), channels);
  }
  return out;
}

}  // namespace

TEST_CASE("live source: new takes restyle the stream on the same connection, from where its gait is") {
  const StreamLines lines;
  Live l;  // a window of 10 s holds the whole 9 s stream: every frame stays to compare
  const LiveStyleSpec marching = spec({1.0});
  l.connect(marching);
  l.stream->send(lines.lines(0, 300));
  l.wait_lines(300);

  // The same takes at another strength: handed on, no styler made.
  LiveStyleSpec softer = marching;
  softer.strengths = {0.5};
  l.live.set_style(softer);
  CHECK_FALSE(l.live.status().restyling);
  l.stream->send(lines.lines(300, 400));
  l.wait_lines(400);
  CHECK(l.live.status().strengths == std::vector<double>{0.5});

  // Other takes (a style added, as a mix of three takes would): the stream goes on, styled as
  // before, until the new styler is made; from then on the new one styles it.
  LiveStyleSpec two;
  two.takes = {marching.takes[0], load("cmu142_walk_joy.bvh"), marching.takes[1]};
  two.strengths = {1.0, 0.25};
  l.live.set_style(two);
  CHECK(l.live.status().restyling);
  CHECK(live_status_line(l.live.status()).find("restyling with the new takes") != std::string::npos);
  int sent = 400;
  while (l.live.status().restyling) {  // a frame at a time until the worker takes the new one up
    REQUIRE(sent < lines.clip->frames());
    l.stream->send(lines.line(sent++));
    l.wait_lines(sent);
    l.live.wait_until([](const LiveStatus& s) { return !s.restyling; }, std::chrono::milliseconds(20));
  }
  l.stream->send(lines.lines(sent, sent + 60));
  sent += 60;
  l.wait_lines(sent);
  l.live.poll();
  const LiveStatus& s = l.live.status();
  CHECK(s.state == LiveState::kStreaming);  // the same connection throughout
  CHECK(s.styled == sent);
  CHECK(s.skipped == 0);
  CHECK(s.restyle_error.empty());
  CHECK(s.strengths == std::vector<double>{1.0, 0.25});
  // Strengths of the new takes' count are taken.
  l.live.set_strengths({0.5, 0.5});
  l.stream->send(lines.lines(sent, sent + 80));
  sent += 80;
  l.wait_lines(sent);
  CHECK(l.live.status().strengths == std::vector<double>{0.5, 0.5});
  CHECK(l.live.status().strength_error.empty());

  // Each frame as one of the two stylers alone gives it, bit for bit: the first up to the frame
  // the new one was taken up at, the new one after, as if it had styled the stream from its start.
  l.live.poll();
  REQUIRE(l.live.window_first_frame() == 0);
  const Eigen::MatrixXd& shown = l.live.styled()->motion;
  REQUIRE(shown.rows() == sent);
  const Skeleton& skeleton = lines.clip->skeleton;
  LiveStyle before(skeleton, lines.clip->fps(), marching);
  Eigen::MatrixXd old_rows(sent, skeleton.channel_count);
  old_rows.topRows(300) = styled_alone(before, lines, 0, 300);
  before.set_strengths({0.5});
  old_rows.bottomRows(sent - 300) = styled_alone(before, lines, 300, sent);
  LiveStyle after(skeleton, lines.clip->fps(), two);
  Eigen::MatrixXd new_rows(sent, skeleton.channel_count);
  const int set_at = sent - 80;
  new_rows.topRows(set_at) = styled_alone(after, lines, 0, set_at);
  after.set_strengths({0.5, 0.5});
  new_rows.bottomRows(80) = styled_alone(after, lines, set_at, sent);
  int taken_up = 0;
  while (taken_up < sent && shown.row(taken_up) == old_rows.row(taken_up)) ++taken_up;
  CHECK(taken_up >= 400);        // not before the takes were set
  CHECK(taken_up <= sent - 140);  // the last frame before the restyle was seen done, at the latest
  for (int f = taken_up; f < sent; ++f) REQUIRE(shown.row(f) == new_rows.row(f));
  CHECK((new_rows.row(sent - 1) - old_rows.row(sent - 1)).cwiseAbs().maxCoeff() > 1.0);  // the takes differ

  // Takes that cannot style the stream (a neutral too short to hold a gait cycle): said, and the
  // stream styled on as it was.
  LiveStyleSpec bad = two;
  auto short_neutral = std::make_shared<Clip>(*two.takes[0]);
  short_neutral->motion = Eigen::MatrixXd(short_neutral->motion.topRows(10));
  bad.takes[0] = short_neutral;
  l.live.set_style(bad);
  REQUIRE(l.live.wait_until([](const LiveStatus& st) { return !st.restyle_error.empty(); }, kPatience));
  CHECK_FALSE(l.live.status().restyling);
  CHECK(l.live.status().restyle_error.find("styled with the takes before") != std::string::npos);
  l.stream->send(lines.lines(sent, sent + 20));
  l.wait_lines(sent + 20);
  l.live.poll();
  CHECK(l.live.status().state == LiveState::kStreaming);
  CHECK(l.live.status().styled == sent + 20);
  CHECK(l.live.status().strengths == std::vector<double>{0.5, 0.5});
  const Eigen::MatrixXd more = styled_alone(after, lines, sent, sent + 20);
  CHECK(l.live.styled()->motion.bottomRows(20) == more);

  // Disconnecting while a styler is being made: the stream ends, nothing waits on the UI thread.
  l.live.set_style(marching);
  l.live.disconnect();
  CHECK_FALSE(l.live.active());
  CHECK_FALSE(l.live.status().restyling);
}

TEST_CASE("live source: takes set while it prepares style the stream once it is made") {
  const StreamLines lines;
  Live l;
  LiveSettings settings;
  settings.address = "fake:1";
  settings.skeleton = test::asset("motions/" + kStream);
  l.live.connect(settings, spec({1.0}));
  LiveStyleSpec two = spec({1.0, 0.5});
  l.live.set_style(two);  // preparing: made after the first styler
  REQUIRE(l.live.wait_until([](const LiveStatus& st) { return st.state == LiveState::kStreaming; }, kPatience));
  int sent = 0;
  while (l.live.status().restyling || l.live.status().strengths.size() != 2) {
    REQUIRE(sent < lines.clip->frames());
    l.stream->send(lines.line(sent++));
    l.wait_lines(sent);
    l.live.wait_until([](const LiveStatus& st) { return !st.restyling; }, std::chrono::milliseconds(20));
  }
  CHECK(l.live.status().strengths == std::vector<double>{1.0, 0.5});
  CHECK(l.live.status().restyle_error.empty());
  CHECK(l.live.status().styled == sent);
}
