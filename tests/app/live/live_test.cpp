// mostyle-cli live and live-send, run as a user runs them, over loopback: every frame served (the
// pass-through styler: served values equal the input's within 1e-6), garbage skipped and counted,
// a reference passed through, a client that never reads dropped while a reading one gets every
// frame, a killed source, SIGTERM, a source awaited and reconnected (--connect-timeout), the
// servers on this machine only unless opened, clients past --max-clients refused, recordings
// whole after a kill, and bad usage.
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

#include "engine/base/atomic_file.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/io/bvh/bvh_write.h"
#include "engine/live/axis_stream.h"
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
// connect_timeout: --connect-timeout's value ("0": one try, the end when the source closes, as
// the tests that read a stream to its end need); "": not given (wait for ever).
std::vector<std::string> live_args(int source_port, const std::string& skeleton, const std::vector<std::string>& more,
                                   const std::string& connect_timeout = "0") {
  std::vector<std::string> a{"live",       "--connect", "127.0.0.1:" + std::to_string(source_port),
                             "--skeleton", skeleton,    "--neutral",
                             skeleton,     "--style",   kJoy,
                             "--strength", "0",         "--serve",
                             "0"};
  if (!connect_timeout.empty()) a.insert(a.end(), {"--connect-timeout", connect_timeout});
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
                         test::shared_motion("bandai_walk_old.bvh"), "--strength", strength, "--serve", "0",
                         "--connect-timeout", "0"},
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

// How many times `text` holds `part`.
long occurrences(const std::string& text, const std::string& part) {
  long n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + part.size())) ++n;
  return n;
}

// Long enough for several tries of a source not there (0.25 s, 0.5 s, 1 s apart).
constexpr auto kSeveralTries = std::chrono::milliseconds(1800);

TEST_CASE("live waits for its source, and for it again after it drops, saying so once each time; its client stays "
          "connected and the new stream starts afresh",
          "[cli][live]") {
  Sandbox box;
  const Clip clip = read_bvh_file(kHappy);
  int port = 0;
  int source_listen = test::bound_not_listening(&port);
  test::CliProcess live(live_args(port, kHappy, {"--record", box.path("out.bvh")}, ""), box.path("live.err"));
  const int served = live.port();
  REQUIRE(served > 0);
  const int client = test::connect_local(served);
  REQUIRE(client >= 0);
  REQUIRE(test::eventually([&] { return live.err().find("note: waiting for 127.0.0.1:") != std::string::npos; }));
  std::this_thread::sleep_for(kSeveralTries);
  REQUIRE(::listen(source_listen, 4) == 0);

  // The first stream, then the source gone (nothing listening) for several tries.
  int source = test::accept_within(source_listen);
  REQUIRE(source >= 0);
  std::string stream;
  for (int f = 0; f < 3; ++f) stream += frame_line(clip, f);
  test::send_all(source, stream);
  REQUIRE(test::read_lines(client, 3).size() == 3);
  ::close(source);
  ::close(source_listen);
  REQUIRE(test::eventually([&] { return live.err().find("closed after 3 lines; waiting for it again") != std::string::npos; }));
  std::this_thread::sleep_for(kSeveralTries);

  // The source back, its stream another avatar's (a new stream's first frame picks the avatar).
  source_listen = test::listen_local_on(port);
  REQUIRE(source_listen >= 0);
  source = test::accept_within(source_listen);
  REQUIRE(source >= 0);
  stream.clear();
  const int n = clip.skeleton.channel_count;
  for (int f = 3; f < 6; ++f) append_axis_line(&stream, 1, "Avatar01", nullptr, 0, clip.motion.row(f).data(), n);
  test::send_all(source, stream);
  const std::vector<std::string> lines = test::read_lines(client, 3);  // the same client, still connected
  REQUIRE(lines.size() == 3);
  for (int f = 3; f < 6; ++f) {
    AxisFrame frame;
    std::string reason;
    REQUIRE(parse_axis_line(lines[static_cast<size_t>(f - 3)], n, &frame, &reason) == AxisLineStatus::kOk);
    CHECK(frame.avatar_index == 1);
    CHECK(frame.avatar_name == "Avatar01");
    for (int c = 0; c < n; ++c) CHECK(std::abs(frame.values[static_cast<size_t>(c)] - clip.motion(f, c)) <= kServed * std::max(1.0, std::abs(clip.motion(f, c))));
  }
  live.signal(SIGTERM);
  CHECK(live.wait() == 0);
  const std::string err = live.err();
  INFO(err);
  CHECK(summary(live.out()) == std::vector<long long>{6, 6, 0, 1, 0});
  check_recording(box.path("out.bvh"), clip, 6);
  // Once each: waiting at the start, connected, closed, connected again; not once per try.
  CHECK(occurrences(err, "mostyle: note: waiting for 127.0.0.1:" + std::to_string(port) + " (Connection refused)\n") == 1);
  CHECK(occurrences(err, "mostyle: note: connected to 127.0.0.1:" + std::to_string(port) + "\n") == 2);
  CHECK(occurrences(err, " closed after 3 lines; waiting for it again\n") == 1);
  CHECK(std::count(err.begin(), err.end(), '\n') == 4);
  for (int fd : {client, source, source_listen}) ::close(fd);
}

TEST_CASE("live stopped at Ctrl-C while it waits for its source ends cleanly, its client told the end",
          "[cli][live]") {
  Sandbox box;
  int port = 0;
  const int source_listen = test::bound_not_listening(&port);
  test::CliProcess live(live_args(port, kHappy, {}, ""), box.path("live.err"));
  const int served = live.port();
  REQUIRE(served > 0);
  const int client = test::connect_local(served);
  REQUIRE(test::eventually([&] { return live.err().find("note: waiting for 127.0.0.1:") != std::string::npos; }));
  live.signal(SIGINT);
  CHECK(live.wait() == 0);
  CHECK(summary(live.out()) == std::vector<long long>{0, 0, 0, 1, 0});
  CHECK(test::read_lines(client).empty());
  for (int fd : {client, source_listen}) ::close(fd);
}

TEST_CASE("live --reconnect, kept for older command lines, waits as live does", "[cli][live]") {
  Sandbox box;
  const Clip clip = read_bvh_file(kHappy);
  int port = 0;
  const int source_listen = test::bound_not_listening(&port);
  test::CliProcess live(live_args(port, kHappy, {"--reconnect"}, ""), box.path("live.err"));
  const int served = live.port();
  REQUIRE(served > 0);
  const int client = test::connect_local(served);
  REQUIRE(test::eventually([&] { return live.err().find("note: waiting for 127.0.0.1:") != std::string::npos; }));
  REQUIRE(::listen(source_listen, 4) == 0);
  const int source = test::accept_within(source_listen);
  REQUIRE(source >= 0);
  test::send_all(source, frame_line(clip, 0));
  CHECK(test::read_lines(client, 1).size() == 1);
  live.signal(SIGTERM);
  CHECK(live.wait() == 0);
  for (int fd : {client, source, source_listen}) ::close(fd);
}

TEST_CASE("live --connect-timeout gives up on a source not there, at the start with status 1, after a drop with 0",
          "[cli][live]") {
  Sandbox box;
  const Clip clip = read_bvh_file(kHappy);
  SECTION("at the start: one note, then the error, after the timeout") {
    int port = 0;
    const int closed = test::bound_not_listening(&port);
    const std::string connect = "127.0.0.1:" + std::to_string(port);
    const auto t0 = test::TestClock::now();
    const test::CliRun r = box.cli("live --connect " + connect + " --skeleton " + test::shell_quoted(kHappy) +
                                   " --neutral " + test::shell_quoted(kHappy) + " --style " + test::shell_quoted(kJoy) +
                                   " --connect-timeout 1");
    const double waited = std::chrono::duration<double>(test::TestClock::now() - t0).count();
    INFO(r.err);
    CHECK(r.status == 1);
    CHECK(waited >= 1.0);
    CHECK(r.err == "mostyle: note: waiting for " + connect + " (Connection refused)\nmostyle: cannot connect to " +
                       connect + " within 1 s (--connect-timeout): Connection refused\n");
    ::close(closed);
  }
  SECTION("after a drop: the stream's end, once the source has not come back within the timeout") {
    int port = 0;
    int source_listen = test::listen_local(&port);
    test::CliProcess live(live_args(port, kHappy, {}, "1.5"), box.path("live.err"));
    const int served = live.port();
    REQUIRE(served > 0);
    const int client = test::connect_local(served);
    const int source = test::accept_within(source_listen);
    REQUIRE(source >= 0);
    std::string stream;
    for (int f = 0; f < 3; ++f) stream += frame_line(clip, f);
    test::send_all(source, stream);
    REQUIRE(test::read_lines(client, 3).size() == 3);
    ::close(source_listen);
    ::close(source);
    const auto t0 = test::TestClock::now();
    CHECK(test::read_lines(client).empty());  // the end of the stream, once live gives up
    CHECK(std::chrono::duration<double>(test::TestClock::now() - t0).count() >= 1.4);
    CHECK(live.wait() == 0);
    const std::string err = live.err();
    INFO(err);
    CHECK(summary(live.out()) == std::vector<long long>{3, 3, 0, 1, 0});
    CHECK(err.find("mostyle: note: 127.0.0.1:" + std::to_string(port) + " did not come back within 1.5 s (--connect-timeout)\n") !=
          std::string::npos);
    ::close(client);
  }
}

TEST_CASE("live and live-send listen on this machine only unless told an address, and say where", "[cli][live]") {
  // Where each listens is read from the kernel's socket table: nothing is sent to any address
  // but loopback ones.
  Sandbox box;
  SECTION("--serve PORT: bound to 127.0.0.1 alone, which no other machine reaches") {
    test::CliProcess send({"live-send", kHappy, "--serve", "0", "--loop"}, box.path("send.err"));
    const int port = send.port();
    REQUIRE(port > 0);
    CHECK(send.wait_for_output("on 127.0.0.1 port " + std::to_string(port) + " (this machine only); waiting for a client\n"));
    CHECK(test::listening_address(port) == "127.0.0.1");
    errno = 0;
    CHECK(test::connect_to(test::other_loopback(), port) < 0);  // not even 127.0.0.2
    CHECK(errno == ECONNREFUSED);
    const int client = test::connect_local(port);
    CHECK(test::read_lines(client, 5).size() == 5);
    ::close(client);
    send.signal(SIGTERM);
    CHECK(send.wait() == 0);

    int source = 0;
    const int source_listen = test::listen_local(&source);
    test::CliProcess live(live_args(source, kHappy, {}), box.path("live.err"));
    const int served = live.port();
    REQUIRE(served > 0);
    CHECK(live.wait_for_output("live: serving on 127.0.0.1 port " + std::to_string(served) + " (this machine only)\n"));
    CHECK(test::listening_address(served) == "127.0.0.1");
    live.signal(SIGTERM);
    CHECK(live.wait() == 0);
    ::close(source_listen);
  }
  SECTION("--serve 0.0.0.0:PORT opens it to every IPv4 interface on purpose") {
    test::CliProcess send({"live-send", kHappy, "--serve", "0.0.0.0:0", "--loop"}, box.path("send.err"));
    const int port = send.port();
    REQUIRE(port > 0);
    CHECK(send.wait_for_output("on 0.0.0.0 port " + std::to_string(port) + " (every IPv4 interface);"));
    CHECK(test::listening_address(port) == "0.0.0.0");
    const int other = test::connect_to(test::other_loopback(), port);
    CHECK(other >= 0);
    CHECK(test::read_lines(other, 2).size() == 2);
    ::close(other);
    const int client = test::connect_local(port);
    CHECK(test::read_lines(client, 2).size() == 2);
    ::close(client);
    send.signal(SIGTERM);
    CHECK(send.wait() == 0);
  }
  SECTION("--serve ADDRESS:PORT: that address only") {
    const std::string address = test::address_text(test::other_loopback());
    test::CliProcess send({"live-send", kHappy, "--serve", address + ":0", "--loop"}, box.path("send.err"));
    const int port = send.port();
    REQUIRE(port > 0);
    CHECK(send.wait_for_output("on " + address + " port " + std::to_string(port)));
    CHECK(test::listening_address(port) == address);
    CHECK(test::connect_local(port) < 0);
    const int client = test::connect_to(test::other_loopback(), port);
    CHECK(client >= 0);
    CHECK(test::read_lines(client, 2).size() == 2);
    ::close(client);
    send.signal(SIGTERM);
    CHECK(send.wait() == 0);
  }
}

TEST_CASE("live-send and live serve --max-clients clients and refuse the next, saying so, serving the others",
          "[cli][live]") {
  Sandbox box;
  const Clip clip = read_bvh_file(kHappy);
  test::CliProcess send({"live-send", kHappy, "--serve", "0", "--loop", "--rate", "480", "--max-clients", "2"},
                        box.path("send.err"));
  const int port = send.port();
  REQUIRE(port > 0);
  const int a = test::connect_local(port), b = test::connect_local(port);
  REQUIRE(test::read_lines(a, 10).size() == 10);
  REQUIRE(test::read_lines(b, 10).size() == 10);
  const int c = test::connect_local(port);  // one past the cap: accepted, closed at once
  REQUIRE(c >= 0);
  CHECK(test::read_lines(c).empty());
  REQUIRE(test::eventually([&] { return send.err().find("refused") != std::string::npos; }));
  CHECK(send.err() == "mostyle: warning: refused a client from 127.0.0.1: 2 clients are connected, the most "
                      "--max-clients allows (1 refused in all)\n");
  // The two served go on, each line the next frame.
  for (int fd : {a, b}) {
    const std::vector<std::string> lines = test::read_lines(fd, 20);
    REQUIRE(lines.size() == 20);
    int first = -1;
    for (int f = 0; f < clip.frames() && first < 0; ++f)
      if (serves_frame(lines[0], clip, f)) first = f;
    REQUIRE(first >= 0);
    for (int k = 1; k < 20; ++k) CHECK(serves_frame(lines[static_cast<size_t>(k)], clip, first + k));
  }
  // A place freed is a place taken, once the server has let go of it.
  const std::string pid = std::to_string(send.pid());
  const int with_b = test::open_descriptors(pid);
  ::close(b);
  REQUIRE(test::eventually([&] { return test::open_descriptors(pid) == with_b - 1; }));
  const int d = test::connect_local(port);
  REQUIRE(test::eventually([&] {
    pollfd p{d, POLLIN, 0};
    return ::poll(&p, 1, 0) == 1;
  }));
  CHECK(test::read_lines(d, 5).size() == 5);
  send.signal(SIGTERM);
  CHECK(send.wait() == 0);
  INFO(send.out());
  CHECK(send.out().find(" frames sent; 3 clients, 0 dropped, 1 refused\n") != std::string::npos);
  for (int fd : {a, c, d}) ::close(fd);

  // live the same (its own flag and line).
  int source = 0;
  const int source_listen = test::listen_local(&source);
  test::CliProcess live(live_args(source, kHappy, {"--max-clients", "1"}), box.path("live.err"));
  const int served = live.port();
  REQUIRE(served > 0);
  const int kept = test::connect_local(served), refused = test::connect_local(served);
  CHECK(test::read_lines(refused).empty());
  const int from = test::accept_within(source_listen);
  REQUIRE(from >= 0);
  test::send_all(from, frame_line(clip, 0) + frame_line(clip, 1));
  const std::vector<std::string> lines = test::read_lines(kept, 2);
  REQUIRE(lines.size() == 2);
  CHECK(serves_frame(lines[1], clip, 1));
  ::close(from);
  CHECK(live.wait() == 0);
  INFO(live.err());
  CHECK(live.err().find("mostyle: warning: refused a client from 127.0.0.1: 1 clients are connected") != std::string::npos);
  CHECK(live.out().find("live: 2 frames in, 2 styled, 0 skipped; 1 clients, 0 dropped, 1 refused\n") != std::string::npos);
  for (int fd : {kept, refused, source_listen}) ::close(fd);
}

TEST_CASE("live-send: a thousand connections opened and closed leave its descriptors and a kept client's stream as "
          "they were",
          "[cli][live]") {
  Sandbox box;
  const Clip clip = read_bvh_file(kHappy);
  test::CliProcess send({"live-send", kHappy, "--serve", "0", "--loop", "--rate", "240"}, box.path("send.err"));
  const int port = send.port();
  REQUIRE(port > 0);
  const int kept = test::connect_local(port);
  REQUIRE(test::read_lines(kept, 1).size() == 1);
  const std::string pid = std::to_string(send.pid());
  const int before = test::open_descriptors(pid);
  REQUIRE(before > 0);
  // The kept client reads all along, on a thread of its own; the stream must stay whole.
  std::atomic<bool> done{false};
  std::vector<std::string> kept_lines;
  std::thread reader([&] {
    std::string partial;
    char buffer[1 << 16];
    while (!done.load()) {
      pollfd p{kept, POLLIN, 0};
      if (::poll(&p, 1, 100) <= 0) continue;
      const ssize_t n = ::recv(kept, buffer, sizeof buffer, 0);
      if (n <= 0) break;
      partial.append(buffer, static_cast<size_t>(n));
      size_t start = 0;
      for (size_t nl; (nl = partial.find('\n', start)) != std::string::npos; start = nl + 1)
        kept_lines.push_back(partial.substr(start, nl - start));
      partial.erase(0, start);
    }
  });
  // In batches of 25 held at once, past the cap of 16, 1000 in all. Once each of a batch has
  // been served (a frame came) or refused (the end came), the server holds no more descriptors
  // than its clients allowed: the kept one and 15 others at most.
  constexpr int kConnections = 1000, kBatch = 25;
  int opened = 0, most = 0;
  for (int round = 0; round < kConnections / kBatch; ++round) {
    std::vector<pollfd> batch;
    for (int k = 0; k < kBatch; ++k) {
      const int fd = test::connect_local(port);
      if (fd >= 0) ++opened;
      batch.push_back({fd, POLLIN, 0});
    }
    REQUIRE(test::eventually([&] {
      return ::poll(batch.data(), batch.size(), 0) == static_cast<int>(batch.size());
    }));
    // A refused client can read the end a moment before the server has closed its side: the
    // count is taken once the server has had that moment (a busy machine stretches it).
    test::eventually([&] { return test::open_descriptors(pid) - before <= 15; });
    most = std::max(most, test::open_descriptors(pid) - before);
    for (const pollfd& p : batch)
      if (p.fd >= 0) ::close(p.fd);
  }
  CHECK(opened == kConnections);
  CHECK(most <= 15);
  // Every connection closed is let go of (each one served finds its peer gone at its next frame).
  CHECK(test::eventually([&] { return test::open_descriptors(pid) == before; }));
  done = true;
  reader.join();
  CHECK(test::open_descriptors(pid) == before);
  send.signal(SIGTERM);
  CHECK(send.wait() == 0);
  INFO(send.err());
  // The kept client's stream: consecutive frames throughout.
  REQUIRE(kept_lines.size() >= 50);
  int first = -1;
  for (int f = 0; f < clip.frames() && first < 0; ++f)
    if (serves_frame(kept_lines[0], clip, f)) first = f;
  REQUIRE(first >= 0);
  for (size_t k = 1; k < kept_lines.size(); ++k) REQUIRE(serves_frame(kept_lines[k], clip, first + static_cast<int>(k)));
  // Each connection served or refused, none dropped as slow.
  std::smatch m;
  const std::string out = send.out();
  REQUIRE(std::regex_search(out, m, std::regex("([0-9]+) clients, ([0-9]+) dropped, ([0-9]+) refused")));
  CHECK(std::stoll(m[1]) + std::stoll(m[3]) == kConnections + 1);
  CHECK(std::stoll(m[2]) == 0);
  CHECK(std::stoll(m[3]) > 0);
  ::close(kept);
}

TEST_CASE("live and live-send refuse bad usage in one line naming the file or option", "[cli][live]") {
  Sandbox box;
  const std::string happy = test::shell_quoted(kHappy), joy = test::shell_quoted(kJoy);
  // A port nothing listens on: bound, never listening.
  int closed_port = 0;
  const int closed = test::bound_not_listening(&closed_port);
  const std::string source = "--connect 127.0.0.1:" + std::to_string(closed_port);
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
       "--serve: expected PORT or ADDRESS:PORT (7001 for this machine only, 0.0.0.0:7001 for every IPv4 interface, "
       "[::]:7001 for every interface), found '70000': the port is not a number from 0 (any free one) to 65535"},
      {"live " + source + " --skeleton " + happy + " --neutral " + happy + " --style " + joy + " --serve localhost:7001",
       "found 'localhost:7001': 'localhost' is not a numeric IPv4 address"},
      {"live " + source + " --skeleton " + happy + " --neutral " + happy + " --style " + joy + " --serve :7001",
       "found ':7001': give the address to listen on before ':'"},
      {"live " + source + " --skeleton " + happy + " --neutral " + happy + " --style " + joy + " --serve ::1:7001",
       "an IPv6 address goes in brackets ([::1]:7001)"},
      {"live " + source + " --skeleton " + happy + " --neutral " + happy + " --style " + joy + " --serve '[1.2.3.4]:7001'",
       "'1.2.3.4' is not an IPv6 address"},
      {"live " + source + " --skeleton " + happy + " --neutral " + happy + " --style " + joy + " --serve 127.0.0.1:x",
       "found '127.0.0.1:x': the port is not a number"},
      {"live " + source + " --skeleton " + happy + " --neutral " + happy + " --style " + joy + " --serve 0 --max-clients 0",
       "--max-clients: expected from 1 to 1024 clients, found 0"},
      {"live " + source + " --skeleton " + happy + " --neutral " + happy + " --style " + joy + " --connect-timeout -1",
       "--connect-timeout: expected seconds from 0 (one try, and the end when the source closes) up, found '-1'"},
      {"live " + source + " --skeleton " + happy + " --neutral " + happy + " --style " + joy + " --connect-timeout soon",
       "--connect-timeout: expected seconds"},
      {"live " + source + " --skeleton " + happy + " --neutral " + happy + " --style " + joy + " --record '" + rec +
           "' --connect-timeout 0",
       "cannot connect to 127.0.0.1:" + std::to_string(closed_port) + ": Connection refused"},
      {"live-send '" + missing + "' --serve 0", missing + ": cannot read"},
      {"live-send " + happy + " --serve 0 --rate -1", "--rate"},
      {"live-send " + happy + " --serve 0 --clients 0", "--clients: expected from 1 to 64 clients, found 0"},
      {"live-send " + happy + " --serve 0 --clients 3 --max-clients 2", "--clients: 3 clients cannot connect with --max-clients 2"},
      {"live-send " + happy + " --serve 0 --max-clients 2000", "--max-clients: expected from 1 to 1024 clients, found 2000"},
      {"live-send " + happy + " --serve 0.0.0.0.0:1", "'0.0.0.0.0' is not a numeric IPv4 address"},
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
