#include "engine/live/stream_styler.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "engine/io/bvh/bvh_read.h"
#include "tests/test_data.h"

using namespace mostyle;

namespace {

constexpr double kWritten = 1e-6;  // relative: a value as append_axis_line writes it (7 digits)

std::shared_ptr<const Clip> load(const std::string& name) {
  return std::make_shared<const Clip>(read_bvh_file(test::asset("motions/" + name)));
}

// What the lines came to: the frames styled (as they came and styled) and the lines skipped.
class Kept : public StreamStyler::Sink {
 public:
  explicit Kept(LiveStyle& live) : live_(live) {}
  LiveStyle& styler() override { return live_; }
  void styled(const AxisFrame& frame, const double* values) override {
    inputs.push_back(frame.values);
    outputs.emplace_back(values, values + frame.values.size());
  }
  void skipped(long long line, const std::string& why) override {
    skips.push_back("line " + std::to_string(line) + ": " + why);
  }

  std::vector<std::vector<double>> inputs, outputs;
  std::vector<std::string> skips;

 private:
  LiveStyle& live_;
};

std::string frame_line(const Clip& take, int frame, int avatar = 0) {
  std::string line;
  append_axis_line(&line, avatar, "Avatar0" + std::to_string(avatar), nullptr, 0, take.motion.row(frame).data(),
                   take.skeleton.channel_count);
  return line;
}

}  // namespace

TEST_CASE("stream styler: a take's frames, cut anywhere, are styled as the styler alone styles them", "[live]") {
  const auto neutral = load("cmu142_walk_happy.bvh"), style = load("cmu142_walk_marching.bvh");
  const auto take = load("cmu142_walk_joy.bvh");
  const int frames = 240, channels = take->skeleton.channel_count;
  std::string stream;
  for (int f = 0; f < frames; ++f) stream += frame_line(*take, f);
  LiveStyle live(take->skeleton, take->fps(), {{neutral, style}, {1.0}});
  Kept kept(live);
  StreamStyler lines(channels);
  for (size_t at = 0; at < stream.size(); at += 997) lines.feed(std::string_view(stream).substr(at, 997), kept);
  lines.end(kept);
  CHECK(kept.skips.empty());
  REQUIRE(kept.inputs.size() == static_cast<size_t>(frames));
  LiveStyle alone(take->skeleton, take->fps(), {{neutral, style}, {1.0}});
  std::vector<double> out(static_cast<size_t>(channels));
  for (int f = 0; f < frames; ++f) {
    const std::vector<double>& in = kept.inputs[static_cast<size_t>(f)];
    for (int c = 0; c < channels; ++c)
      REQUIRE(std::abs(in[static_cast<size_t>(c)] - take->motion(f, c)) <=
              kWritten * std::max(1.0, std::abs(take->motion(f, c))));
    alone.style_frame(in.data(), out.data());
    REQUIRE(kept.outputs[static_cast<size_t>(f)] == out);
  }
}

TEST_CASE("stream styler: lines that give no frame are skipped, each with its number and why", "[live]") {
  const auto neutral = load("cmu142_walk_happy.bvh"), style = load("cmu142_walk_marching.bvh");
  const auto take = load("cmu142_walk_joy.bvh");
  const int channels = take->skeleton.channel_count;
  LiveStyle live(take->skeleton, take->fps(), {{neutral, style}, {0.0}});
  Kept kept(live);
  StreamStyler lines(channels);
  const std::string too_long(max_stream_line_bytes(channels) + 10, '1');
  lines.feed(frame_line(*take, 0) + "0 Avatar00 1 2 3 ||\n" + frame_line(*take, 1, 2) + too_long + "\n\n" +
                 frame_line(*take, 2) + "0 Avatar00 1 2",
             kept);
  lines.end(kept);
  CHECK(kept.outputs.size() == 2);
  REQUIRE(kept.skips.size() == 4);
  CHECK(kept.skips[0].rfind("line 2: expected ", 0) == 0);
  CHECK(kept.skips[1] == "line 3: avatar 2 is not the one styled (0)");
  const std::string longest = std::to_string(max_stream_line_bytes(channels));
  CHECK(kept.skips[2] == "line 4: the line is longer than " + longest + " bytes");
  CHECK(kept.skips[3] == "line 7: the stream ended inside a line");

  // A new stream: its lines numbered from 1, its first frame's avatar the one styled.
  lines.restart();
  kept.skips.clear();
  lines.feed(frame_line(*take, 3, 2) + frame_line(*take, 4, 0), kept);
  lines.end(kept);
  CHECK(kept.outputs.size() == 3);
  CHECK(kept.skips == std::vector<std::string>{"line 2: avatar 0 is not the one styled (2)"});
  CHECK(max_stream_line_bytes(1) == size_t{1} << 16);
}
