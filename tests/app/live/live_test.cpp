// mostyle-cli live and live-send, run as a user runs them, over loopback: every frame served (the
// pass-through styler: served values equal the input's within 1e-6), garbage skipped and counted,
// a reference passed through, a client that never reads dropped while a reading one gets every
// frame, a killed source, SIGTERM, --reconnect, recordings whole after a kill, and bad usage.
// Most tests play the source themselves (a socket in the test), so they send exactly what they
// check; deadlines are generous and ports the system's, so a loaded machine slows them only.
#include <catch2/catch.hpp>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "engine/io/atomic_file.h"
#include "engine/io/axis_stream.h"
#include "engine/io/bvh_io.h"
#include "engine/kinematics/kinematics.h"
#include "tests/app/cli/cli_sandbox.h"
#include "tests/app/live/live_process.h"
#include "tests/test_data.h"

using namespace mostyle;
namespace fs = std::filesystem;

namespace {

// Served values against the frames they came from (7 significant digits on the wire: 5e-7).
constexpr double kServed = 1e-6;

class Sandbox : public test::CliSandbox {
 public:
  Sandbox() : test::CliSandbox("mostyle_live_test") {}
};

const std::string kHappy = test::asset("motions/cmu142_walk_happy.bvh");
const std::string kJoy = test::asset("motions/cmu142_walk_joy.bvh");

std::string frame_line(const Clip& clip, int f, const std::vector<double>& reference = {}) {
  std::string out;
  const int n = clip.skeleton.channel_count;
  append_axis_line(&out, 0, "Avatar00", reference.data(), static_cast<int>(reference.size()),
                   clip.motion.data() + static_cast<Eigen::Index>(f % clip.frames()) * n, n);
  return out;
}

// Whether a served line holds frame f of clip (and, when given, the reference exactly).
bool serves_frame(const std::string& line, const Clip& clip, int f, const std::vector<double>& reference = {}) {
  AxisFrame frame;
  std::string reason;
  if (parse_axis_line(line, clip.skeleton.channel_count, &frame, &reason) != AxisLineStatus::kOk) return false;
  if (frame.avatar_index != 0 || frame.avatar_name != "Avatar00" || frame.reference != reference) return false;
  for (int c = 0; c < clip.skeleton.channel_count; ++c) {
    const double expected = clip.motion(f % clip.frames(), c);
    if (std::abs(frame.values[static_cast<size_t>(c)] - expected) > kServed * std::max(1.0, std::abs(expected)))
      return false;
  }
  return true;
}

// A recording holds frames first .. first + count - 1 of clip, and reads without warnings.
void check_recording(const std::string& path, const Clip& clip, int count, bool whole = true) {
  std::vector<std::string> warnings;
  const Clip rec = read_bvh_file(path, &warnings);
  if (whole) CHECK(warnings.empty());
  REQUIRE(rec.frames() == count);
  CHECK(format_bvh_hierarchy(rec.skeleton) == format_bvh_hierarchy(clip.skeleton));
  for (int f = 0; f < count; ++f)
    for (int c = 0; c < clip.skeleton.channel_count; ++c) {
      const double expected = clip.motion(f % clip.frames(), c);
      REQUIRE(std::abs(rec.motion(f, c) - expected) <= kServed * std::max(1.0, std::abs(expected)));
    }
}

// `live` on a source at 127.0.0.1:source_port, serving on a port of the system's, styling at
// strength 0: each frame as it came, with the pass-through styler and with a real one alike.
std::vector<std::string> live_args(int source_port, const std::string& skeleton, const std::vector<std::string>& more) {
  std::vector<std::string> a{"live",       "--connect", "127.0.0.1:" + std::to_string(source_port),
                             "--skeleton", skeleton,    "--neutral",
                             skeleton,     "--style",   kJoy,
                             "--strength", "0",         "--serve",
                             "0"};
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

// The numbers of live's summary line: frames in, styled, skipped, clients, dropped.
std::vector<long long> summary(const std::string& out) {
  std::smatch m;
  const std::regex pattern("live: ([0-9]+) frames in, ([0-9]+) styled, ([0-9]+) skipped; ([0-9]+) clients, ([0-9]+) dropped");
  if (!std::regex_search(out, m, pattern)) return {};
  std::vector<long long> n;
  for (size_t i = 1; i < m.size(); ++i) n.push_back(std::stoll(m[i]));
  return n;
}

// The test as the source: live connected to it, one client connected to live before any frame.
struct LiveOnTestSource {
  int source_listen = -1, source = -1, client = -1, served_port = -1;
  std::unique_ptr<test::CliProcess> live;

  LiveOnTestSource(const Sandbox& box, const std::string& skeleton, const std::vector<std::string>& more) {
    int port = 0;
    source_listen = test::listen_local(&port);
    live = std::make_unique<test::CliProcess>(live_args(port, skeleton, more), box.path("live.err"));
    served_port = live->port();
    REQUIRE(served_port > 0);
    client = test::connect_local(served_port);
    REQUIRE(client >= 0);
    source = test::accept_within(source_listen);
    REQUIRE(source >= 0);
  }
  ~LiveOnTestSource() {
    for (int fd : {source_listen, source, client})
      if (fd >= 0) ::close(fd);
  }
  void close_source() {
    ::close(source);
    source = -1;
  }
};

void serves_every_frame(const std::string& file) {
  Sandbox box;
  const Clip clip = read_bvh_file(file);
  LiveOnTestSource s(box, file, {"--record", box.path("out.bvh"), "--record-input", box.path("in.bvh")});
  std::thread source([&] {
    std::string all;
    for (int f = 0; f < clip.frames(); ++f) all += frame_line(clip, f);
    test::send_all(s.source, all);
    s.close_source();
  });
  const std::vector<std::string> lines = test::read_lines(s.client, clip.frames());
  source.join();
  REQUIRE(static_cast<int>(lines.size()) == clip.frames());
  for (int f = 0; f < clip.frames(); ++f) REQUIRE(serves_frame(lines[static_cast<size_t>(f)], clip, f));
  CHECK(test::read_lines(s.client).empty());  // then the end of the stream
  CHECK(s.live->wait() == 0);
  INFO(s.live->err());
  CHECK(summary(s.live->out()) == std::vector<long long>{clip.frames(), clip.frames(), 0, 1, 0});
  check_recording(box.path("out.bvh"), clip, clip.frames());
  check_recording(box.path("in.bvh"), clip, clip.frames());
}

// A take replayed through `live-send --clients 2` -> `live` (the real styler: Bandai normal -> old
// at `strength`) -> a reading client, with a second client reading live-send itself (its second
// client starts it, so live and its client miss nothing). Returns the frames served, parsed.
Clip replay_through_live(const Sandbox& box, const std::string& take, const std::string& strength) {
  const Clip clip = read_bvh_file(take);
  test::CliProcess send({"live-send", take, "--serve", "0", "--clients", "2", "--rate", "1000"}, box.path("send.err"));
  const int source_port = send.port();
  REQUIRE(source_port > 0);
  test::CliProcess live({"live", "--connect", "127.0.0.1:" + std::to_string(source_port), "--skeleton", take,
                         "--neutral", test::shared_motion("bandai_walk_normal.bvh"), "--style",
                         test::shared_motion("bandai_walk_old.bvh"), "--strength", strength, "--serve", "0"},
                        box.path("live.err"));
  const int served_port = live.port();
  INFO(live.err());
  REQUIRE(served_port > 0);
  const int client = test::connect_local(served_port);
  REQUIRE(client >= 0);
  const int direct = test::connect_local(source_port);  // live takes its client before this starts the frames
  REQUIRE(direct >= 0);
  std::vector<std::string> sent;
  std::thread reader([&] { sent = test::read_lines(direct); });
  const std::vector<std::string> lines = test::read_lines(client);
  reader.join();
  ::close(direct);
  ::close(client);
  CHECK(live.wait() == 0);
  CHECK(send.wait() == 0);
  CHECK(static_cast<int>(sent.size()) == clip.frames());
  REQUIRE(static_cast<int>(lines.size()) == clip.frames());  // every frame served
  CHECK(summary(live.out()) == std::vector<long long>{clip.frames(), clip.frames(), 0, 1, 0});
  Clip served = clip;
  for (int f = 0; f < clip.frames(); ++f) {
    AxisFrame frame;
    std::string reason;
    REQUIRE(parse_axis_line(lines[static_cast<size_t>(f)], clip.skeleton.channel_count, &frame, &reason) ==
            AxisLineStatus::kOk);
    for (int c = 0; c < clip.skeleton.channel_count; ++c) served.motion(f, c) = frame.values[static_cast<size_t>(c)];
  }
  return served;
}

// The standing height of a skeleton's rest pose, file units.
double rest_height(const Skeleton& skeleton) {
  double low = 0.0, high = 0.0;
  for (const Eigen::Vector3d& p : rest_positions(skeleton)) {
    low = std::min(low, p.y());
    high = std::max(high, p.y());
  }
  return high - low;
}

// The farthest any joint of `a` is from the same joint of `b` (one skeleton), over all frames.
double farthest_joint(const Clip& a, const Clip& b) {
  const Eigen::MatrixXd pa = joint_positions(a), pb = joint_positions(b);
  double out = 0.0;
  for (Eigen::Index f = 0; f < pa.rows(); ++f)
    for (Eigen::Index j = 0; j < pa.cols() / 3; ++j)
      out = std::max(out, (pa.block<1, 3>(f, 3 * j) - pb.block<1, 3>(f, 3 * j)).norm());
  return out;
}

}  // namespace

TEST_CASE("live-send -> live with a real style -> a client: every frame arrives; strength 0 serves the stream",
          "[cli][live]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  Sandbox box;
  const Clip clip = read_bvh_file(kHappy);
  const double height = rest_height(clip.skeleton);
  SECTION("strength 0: each served frame is the stream's, every joint within 1e-4 of the body's height") {
    const Clip served = replay_through_live(box, kHappy, "0");
    CHECK(farthest_joint(served, clip) <= 1e-4 * height);
  }
  SECTION("strength 1: every frame served, styled") {
    const Clip served = replay_through_live(box, kHappy, "1");
    CHECK(farthest_joint(served, clip) > 0.01 * height);
  }
}

TEST_CASE("live serves every frame of a take as it came (pass-through styler), and records both streams",
          "[cli][live]") {
  serves_every_frame(kHappy);
}

TEST_CASE("live serves every frame of a Bandai take as it came", "[cli][live]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  serves_every_frame(test::shared_motion("bandai_walk_normal.bvh"));
}

TEST_CASE("live skips garbage lines amid a stream, counts them, warns, and serves the rest", "[cli][live]") {
  Sandbox box;
  const Clip clip = read_bvh_file(kHappy);
  LiveOnTestSource s(box, kHappy, {});
  std::string stream;
  for (int f = 0; f < 10; ++f) stream += frame_line(clip, f);
  std::string short_line = frame_line(clip, 10);
  short_line.erase(short_line.rfind(' ', short_line.size() - 5), short_line.size());  // the last value off
  stream += short_line + " ||\n";                               // line 11: 95 values
  stream += "hello\n";                                          // line 12
  stream += std::string("0 Avatar00 \x01\x02\xff ||\n");        // line 13
  std::string no_bars = frame_line(clip, 10);
  stream += no_bars.substr(0, no_bars.size() - 3) + "\n";      // line 14: no "||"
  std::string nan_line = frame_line(clip, 10);
  nan_line.replace(nan_line.find(' ', 12), 1, " nan ");        // line 15: a value not finite
  stream += nan_line;
  stream += std::string(100000, '7') + "\n";                   // line 16: over-long
  for (int f = 10; f < 20; ++f) stream += frame_line(clip, f);
  std::thread source([&] {
    test::send_all(s.source, stream);
    s.close_source();
  });
  const std::vector<std::string> lines = test::read_lines(s.client);
  source.join();
  REQUIRE(lines.size() == 20);
  for (int f = 0; f < 20; ++f) CHECK(serves_frame(lines[static_cast<size_t>(f)], clip, f));
  CHECK(s.live->wait() == 0);
  const std::string err = s.live->err();
  INFO(err);
  CHECK(summary(s.live->out()) == std::vector<long long>{26, 20, 6, 1, 0});
  // The first bad line is named; later ones within the second are counted, not each warned about.
  CHECK(err.find("mostyle: warning: 127.0.0.1:") != std::string::npos);
  CHECK(err.find(" line 11: expected 96 values (102 with a reference), found 95; frame skipped (1 skipped in all)\n") !=
        std::string::npos);
  const auto warnings = std::count(err.begin(), err.end(), '\n');
  CHECK(warnings >= 2);  // the note "connected to", one warning at least
  CHECK(warnings <= 7);
}

TEST_CASE("live passes a reference's six values through and records the channels only", "[cli][live]") {
  Sandbox box;
  const Clip clip = read_bvh_file(kHappy);
  LiveOnTestSource s(box, kHappy, {"--record", box.path("out.bvh")});
  const std::vector<double> reference{1.25, -2.0, 1.0 / 3.0, 90.0, 0.0, -45.5};
  std::string stream;
  for (int f = 0; f < 30; ++f) stream += frame_line(clip, f, reference);
  test::send_all(s.source, stream);
  s.close_source();
  const std::vector<std::string> lines = test::read_lines(s.client);
  REQUIRE(lines.size() == 30);
  for (int f = 0; f < 30; ++f) CHECK(serves_frame(lines[static_cast<size_t>(f)], clip, f, reference));
  CHECK(s.live->wait() == 0);
  check_recording(box.path("out.bvh"), clip, 30);
}

TEST_CASE("live drops a client that never reads; a reading client gets every frame", "[cli][live]") {
  Sandbox box;
  const Clip clip = read_bvh_file(kHappy);
  LiveOnTestSource s(box, kHappy, {});
  // The second client reads nothing, with a small window: its frames pile up in live's queue.
  const int idle = test::connect_local(s.served_port, 4096);
  REQUIRE(idle >= 0);
  const int total = 8 * clip.frames();  // about 7 MB, several times the queue's bound
  std::atomic<int> received{0};
  std::thread source([&] {
    // Paced by the reading client (never more than 200 frames ahead of it), so that only the
    // idle client's queue grows, however slow the machine.
    std::string chunk;
    for (int f = 0; f < total; f += 100) {
      while (f - received.load() > 200) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      chunk.clear();
      for (int g = f; g < std::min(total, f + 100); ++g) chunk += frame_line(clip, g);
      if (!test::send_all(s.source, chunk)) break;
    }
    s.close_source();
  });
  const std::vector<std::string> lines =
      test::read_lines(s.client, total, [&](size_t n) { received.store(static_cast<int>(n)); });
  source.join();
  REQUIRE(static_cast<int>(lines.size()) == total);
  for (int f = 0; f < total; f += 7) REQUIRE(serves_frame(lines[static_cast<size_t>(f)], clip, f));
  CHECK(serves_frame(lines.back(), clip, total - 1));
  CHECK(s.live->wait() == 0);
  INFO(s.live->err());
  CHECK(summary(s.live->out()) == std::vector<long long>{total, total, 0, 2, 1});
  ::close(idle);
}

TEST_CASE("live-send serves a take's frames from the first, then closes; live ends with 0 when it is killed",
          "[cli][live]") {
  Sandbox box;
  const Clip clip = read_bvh_file(kHappy);
  SECTION("a client gets every frame, from the first (live-send waits for it), then the end") {
    test::CliProcess send({"live-send", kHappy, "--serve", "0", "--rate", "2000"}, box.path("send.err"));
    const int port = send.port();
    REQUIRE(port > 0);
    const int client = test::connect_local(port);
    const std::vector<std::string> lines = test::read_lines(client);
    ::close(client);
    REQUIRE(static_cast<int>(lines.size()) == clip.frames());
    for (int f = 0; f < clip.frames(); ++f) REQUIRE(serves_frame(lines[static_cast<size_t>(f)], clip, f));
    CHECK(send.wait() == 0);
    CHECK(send.out().find("live-send: 1080 frames sent; 1 clients, 0 dropped") != std::string::npos);
  }
  SECTION("live-send killed mid-stream: live ends with 0, its recordings whole with the frames it got") {
    test::CliProcess send({"live-send", kHappy, "--serve", "0", "--rate", "240", "--loop"}, box.path("send.err"));
    const int port = send.port();
    REQUIRE(port > 0);
    test::CliProcess live(live_args(port, kHappy, {"--record", box.path("out.bvh"), "--record-input", box.path("in.bvh")}),
                          box.path("live.err"));
    REQUIRE(live.port() > 0);
    REQUIRE(test::eventually([&] {
      return fs::exists(box.path("in.bvh")) && read_bvh_file(box.path("in.bvh")).frames() >= 30;
    }));
    send.signal(SIGKILL);
    CHECK(live.wait() == 0);
    INFO(live.err());
    const std::vector<long long> n = summary(live.out());
    REQUIRE(n.size() == 5);
    CHECK(n[0] == n[1]);
    CHECK(n[2] == 0);
    check_recording(box.path("out.bvh"), clip, static_cast<int>(n[1]));
    check_recording(box.path("in.bvh"), clip, static_cast<int>(n[1]));
  }
}

TEST_CASE("live killed with SIGKILL mid-stream leaves recordings that read whole", "[cli][live]") {
  Sandbox box;
  const Clip clip = read_bvh_file(kHappy);
  test::CliProcess send({"live-send", kHappy, "--serve", "0", "--rate", "480", "--loop"}, box.path("send.err"));
  const int port = send.port();
  REQUIRE(port > 0);
  test::CliProcess live(live_args(port, kHappy, {"--record", box.path("out.bvh")}), box.path("live.err"));
  REQUIRE(live.port() > 0);
  REQUIRE(test::eventually([&] { return fs::exists(box.path("out.bvh")) && read_bvh_file(box.path("out.bvh")).frames() >= 50; }));
  live.signal(SIGKILL);
  CHECK(live.wait() == -1);
  send.signal(SIGTERM);
  CHECK(send.wait() == 0);
  // The count may be one frame behind the lines (killed between the two writes): one warning.
  std::vector<std::string> warnings;
  const Clip rec = read_bvh_file(box.path("out.bvh"), &warnings);
  CHECK(warnings.size() <= 1);
  check_recording(box.path("out.bvh"), clip, rec.frames(), false);
  // Every line after Frame Time holds all the channels, as Blender's importer needs.
  const std::string text = read_file(box.path("out.bvh"));
  std::istringstream in(text.substr(text.find('\n', text.find("Frame Time:"))));
  int lines = 0;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    int n = 0;
    for (std::string w; words >> w;) ++n;
    if (n == 0) continue;
    CHECK(n == clip.skeleton.channel_count);
    ++lines;
  }
  CHECK(lines == rec.frames());
}

TEST_CASE("live ends cleanly at SIGTERM, its recording complete", "[cli][live]") {
  Sandbox box;
  const Clip clip = read_bvh_file(kHappy);
  LiveOnTestSource s(box, kHappy, {"--record", box.path("out.bvh")});
  std::string stream;
  for (int f = 0; f < 5; ++f) stream += frame_line(clip, f);
  test::send_all(s.source, stream);
  REQUIRE(test::read_lines(s.client, 5).size() == 5);
  s.live->signal(SIGTERM);
  CHECK(s.live->wait() == 0);
  CHECK(summary(s.live->out()) == std::vector<long long>{5, 5, 0, 1, 0});
  check_recording(box.path("out.bvh"), clip, 5);
  CHECK(test::read_lines(s.client).empty());  // clients get the end of the stream
}

TEST_CASE("live --reconnect waits for its source, and for it again after it closes", "[cli][live]") {
  Sandbox box;
  const Clip clip = read_bvh_file(kHappy);
  // A port bound but not yet listening: connections to it are refused until listen().
  const int source_listen = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  REQUIRE(::bind(source_listen, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0);
  socklen_t length = sizeof a;
  ::getsockname(source_listen, reinterpret_cast<sockaddr*>(&a), &length);
  test::CliProcess live(live_args(ntohs(a.sin_port), kHappy, {"--reconnect", "--record", box.path("out.bvh")}),
                        box.path("live.err"));
  const int served = live.port();
  REQUIRE(served > 0);
  const int client = test::connect_local(served);
  REQUIRE(test::eventually([&] { return live.err().find("waiting for 127.0.0.1:") != std::string::npos; }));
  REQUIRE(::listen(source_listen, 4) == 0);
  for (int round = 0; round < 2; ++round) {
    const int source = test::accept_within(source_listen);
    REQUIRE(source >= 0);
    std::string stream;
    for (int f = 3 * round; f < 3 * round + 3; ++f) stream += frame_line(clip, f);
    test::send_all(source, stream);
    REQUIRE(test::read_lines(client, 3).size() == 3);
    ::close(source);
  }
  live.signal(SIGTERM);
  CHECK(live.wait() == 0);
  INFO(live.err());
  CHECK(summary(live.out()) == std::vector<long long>{6, 6, 0, 1, 0});
  check_recording(box.path("out.bvh"), clip, 6);
  ::close(client);
  ::close(source_listen);
}

TEST_CASE("live and live-send refuse bad usage in one line naming the file or option", "[cli][live]") {
  Sandbox box;
  const std::string happy = test::shell_quoted(kHappy), joy = test::shell_quoted(kJoy);
  // A port nothing listens on: bound, never listening.
  const int closed = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(closed, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t length = sizeof a;
  ::getsockname(closed, reinterpret_cast<sockaddr*>(&a), &length);
  const std::string source = "--connect 127.0.0.1:" + std::to_string(ntohs(a.sin_port));
  const std::string missing = box.path("missing.bvh");
  const std::string rec = box.path("rec.bvh");
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases{
      {"live " + source + " --skeleton '" + missing + "' --neutral " + happy + " --style " + joy, missing + ": cannot read"},
      {"live " + source + " --skeleton " + happy + " --neutral '" + missing + "' --style " + joy, missing + ": cannot read"},
      {"live " + source + " --skeleton " + happy + " --neutral " + happy, "--neutral needs at least one --style"},
      {"live " + source + " --skeleton " + happy + " --mix " + happy + " " + joy + " --weights 0.5,0.6", "sum"},
      {"live " + source + " --skeleton " + happy + " --mix " + happy + " " + joy + " --weights 1", "expected 2 weights"},
      {"live " + source + " --skeleton " + happy + " --mix " + happy + " " + joy + " --neutral " + happy + " --style " + joy,
       "give --neutral with --style"},
      {"live " + source + " --skeleton " + happy + " --neutral " + happy + " --style " + joy + " --strength 1,2",
       "expected 1 strengths, one per --style, found 2"},
      {"live " + source + " --skeleton " + happy + " --neutral " + happy + " --style " + joy + " --record '" +
           box.path("out.glb") + "'",
       "out.glb: --record writes BVH"},
      {"live --connect nowhere --skeleton " + happy + " --neutral " + happy + " --style " + joy, "--connect: expected HOST:PORT"},
      {"live " + source + " --skeleton " + happy + " --neutral " + happy + " --style " + joy + " --serve 70000",
       "--serve: expected a port"},
      {"live " + source + " --skeleton " + happy + " --neutral " + happy + " --style " + joy + " --record '" + rec + "'",
       "cannot connect to 127.0.0.1:"},
      {"live-send '" + missing + "' --serve 0", missing + ": cannot read"},
      {"live-send " + happy + " --serve 0 --rate -1", "--rate"},
      {"live-send " + happy + " --serve 0 --clients 0", "--clients: expected from 1 to 64 clients, found 0"},
  };
  for (const Case& c : cases) {
    INFO(c.args);
    const test::CliRun r = box.cli(c.args);
    INFO(r.err);
    CHECK(r.status == 1);
    CHECK(r.err.rfind("mostyle: ", 0) == 0);
    CHECK(r.err.find(c.message) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
  CHECK_FALSE(fs::exists(rec));  // no recording from a run that never streamed
  CHECK(box.count_files() == 0);
  ::close(closed);
}
