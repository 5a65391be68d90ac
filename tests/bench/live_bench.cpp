// Live streams (Axis Neuron BVH broadcasting): the cost of one line for a 59-joint Axis skeleton
// (parse, format, split from TCP chunks), and the latency over loopback from a source sending a
// frame to a client receiving it through `mostyle-cli live` (its styler as built), against one
// plain loopback hop. Latencies are each frame's own (the next frame leaves once the last came),
// as p50 / p99 / max counters in microseconds. BM_LiveSendReplay replays a 20 s 120 fps walk at its
// own rate through `live-send` -> `live` (the real styler, Bandai normal -> old) -> a client, and
// counts the frames reaching the client within 8.3 ms (one frame) of the source sending them.
#include <benchmark/benchmark.h>
#include <netinet/tcp.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <cstdlib>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "engine/io/bvh/bvh_read.h"
#include "engine/io/bvh/bvh_write.h"
#include "engine/live/axis_stream.h"
#include "tests/app/live/live_process.h"

namespace {

using mostyle::AxisFrame;
using mostyle::AxisLineSplitter;
namespace fs = std::filesystem;

// Axis's 59-joint skeleton with "displacement" on: 6 channels a joint, 354 values a line;
// without it 180 (the hips' 6 and 3 a joint). Values as Axis streams them: positions in cm,
// rotations in degrees, with a few decimals.
std::vector<std::string> axis_lines(int channels, int count) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> angle(-180.0, 180.0);
  std::vector<std::string> lines(static_cast<size_t>(count));
  std::vector<double> values(static_cast<size_t>(channels));
  for (std::string& line : lines) {
    for (double& v : values) v = angle(rng);
    mostyle::append_axis_line(&line, 0, "Avatar00", nullptr, 0, values.data(), channels);
  }
  return lines;
}

void BM_AxisParse(benchmark::State& state) {
  const int channels = static_cast<int>(state.range(0));
  const std::vector<std::string> lines = axis_lines(channels, 64);
  AxisFrame frame;
  std::string reason;
  size_t i = 0, bytes = 0;
  for (auto _ : state) {
    const std::string& line = lines[i++ % lines.size()];
    benchmark::DoNotOptimize(mostyle::parse_axis_line(line, channels, &frame, &reason));
    bytes += line.size();
  }
  state.SetBytesProcessed(static_cast<int64_t>(bytes));
  state.SetLabel(std::to_string(lines[0].size()) + " bytes a line");
}
BENCHMARK(BM_AxisParse)->Arg(180)->Arg(354);

void BM_AxisFormat(benchmark::State& state) {
  const int channels = static_cast<int>(state.range(0));
  const std::vector<std::string> lines = axis_lines(channels, 64);
  std::vector<AxisFrame> frames(lines.size());
  std::string reason, out;
  for (size_t k = 0; k < lines.size(); ++k) mostyle::parse_axis_line(lines[k], channels, &frames[k], &reason);
  size_t i = 0;
  for (auto _ : state) {
    const AxisFrame& f = frames[i++ % frames.size()];
    out.clear();
    mostyle::append_axis_line(&out, f.avatar_index, f.avatar_name, nullptr, 0, f.values.data(), channels);
    benchmark::DoNotOptimize(out.data());
  }
}
BENCHMARK(BM_AxisFormat)->Arg(180)->Arg(354);

// The splitter over a stream read in 64 KB chunks, per line.
void BM_AxisSplit(benchmark::State& state) {
  const std::vector<std::string> lines = axis_lines(354, 256);
  std::string stream;
  for (const std::string& l : lines) stream += l;
  AxisLineSplitter splitter;
  for (auto _ : state) {
    for (size_t at = 0; at < stream.size(); at += 1 << 16) {
      std::string_view chunk = std::string_view(stream).substr(at, 1 << 16), line;
      while (splitter.next(&chunk, &line)) benchmark::DoNotOptimize(line.data());
    }
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * lines.size()));
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * stream.size()));
}
BENCHMARK(BM_AxisSplit);

// Sends each line on `out` and waits for a whole line on `in`; each wait's time in microseconds.
std::vector<double> round_trips(benchmark::State& state, int out, int in, const std::vector<std::string>& lines) {
  std::vector<double> us;
  std::string partial;
  char buffer[1 << 16];
  size_t i = 0;
  for (auto _ : state) {
    const auto t0 = mostyle::test::TestClock::now();
    if (!mostyle::test::send_all(out, lines[i++ % lines.size()])) {
      state.SkipWithError("send failed");
      break;
    }
    size_t nl;
    while ((nl = partial.find('\n')) == std::string::npos) {
      const ssize_t n = ::recv(in, buffer, sizeof buffer, 0);
      if (n <= 0) break;
      partial.append(buffer, static_cast<size_t>(n));
    }
    if (nl == std::string::npos) {
      state.SkipWithError("the stream ended");
      break;
    }
    partial.erase(0, nl + 1);
    const double seconds = std::chrono::duration<double>(mostyle::test::TestClock::now() - t0).count();
    state.SetIterationTime(seconds);
    us.push_back(seconds * 1e6);
  }
  return us;
}

void report_percentiles(benchmark::State& state, std::vector<double> us) {
  if (us.empty()) return;
  std::sort(us.begin(), us.end());
  state.counters["p50_us"] = us[us.size() / 2];
  state.counters["p99_us"] = us[std::min(us.size() - 1, us.size() * 99 / 100)];
  state.counters["max_us"] = us.back();
}

// One plain TCP hop over loopback (TCP_NODELAY), for scale: live's path is two such hops.
void BM_LoopbackHop(benchmark::State& state) {
  int port = 0;
  const int listener = mostyle::test::listen_local(&port);
  const int a = mostyle::test::connect_local(port);
  const int b = mostyle::test::accept_within(listener);
  const int on = 1;
  ::setsockopt(a, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
  report_percentiles(state, round_trips(state, a, b, axis_lines(96, 64)));
  for (int fd : {listener, a, b}) ::close(fd);
}
BENCHMARK(BM_LoopbackHop)->UseManualTime()->Unit(benchmark::kMicrosecond);

// Source -> live (parse, style, format, send) -> client, on a CMU take's skeleton (96 channels):
// the real takes, so that the bench holds for the real styler too.
void BM_LiveLatency(benchmark::State& state) {
  const std::string happy = std::string(MOSTYLE_ASSETS_DIR) + "/motions/cmu142_walk_happy.bvh";
  const std::string joy = std::string(MOSTYLE_ASSETS_DIR) + "/motions/cmu142_walk_joy.bvh";
  const mostyle::Clip clip = mostyle::read_bvh_file(happy);
  std::vector<std::string> lines(static_cast<size_t>(clip.frames()));
  for (int f = 0; f < clip.frames(); ++f)
    mostyle::append_axis_line(&lines[static_cast<size_t>(f)], 0, "Avatar00", nullptr, 0,
                              clip.motion.data() + static_cast<Eigen::Index>(f) * clip.motion.cols(),
                              static_cast<int>(clip.motion.cols()));
  int port = 0;
  const int listener = mostyle::test::listen_local(&port);
  const std::string err = (fs::temp_directory_path() / ("mostyle_live_bench_" + std::to_string(::getpid()))).string();
  mostyle::test::CliProcess live({"live", "--connect", "127.0.0.1:" + std::to_string(port), "--skeleton", happy,
                                  "--neutral", happy, "--style", joy, "--strength", "0", "--serve", "0",
                                  "--connect-timeout", "0"},
                                 err);
  const int served = live.port();
  const int client = served > 0 ? mostyle::test::connect_local(served) : -1;
  const int source = client >= 0 ? mostyle::test::accept_within(listener) : -1;
  if (source < 0) {
    state.SkipWithError(("live did not start: " + live.err()).c_str());
  } else {
    const int on = 1;
    ::setsockopt(source, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
    // The client's connection is taken by live before the first frame comes (one frame first).
    mostyle::test::send_all(source, lines[0]);
    mostyle::test::read_lines(client, 1);
    report_percentiles(state, round_trips(state, source, client, lines));
    ::close(source);
    live.wait();
  }
  for (int fd : {listener, client}) ::close(fd);
  std::remove(err.c_str());
}
BENCHMARK(BM_LiveLatency)->UseManualTime()->Unit(benchmark::kMicrosecond)->Iterations(5000);

// Reads lines from fd until it closes (or `count` lines came); each line's arrival time.
std::vector<mostyle::test::TestClock::time_point> arrivals(int fd, size_t count) {
  std::vector<mostyle::test::TestClock::time_point> out;
  out.reserve(count);
  char buffer[1 << 16];
  while (out.size() < count) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 60000) <= 0) break;
    const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n <= 0) break;
    const auto now = mostyle::test::TestClock::now();
    for (ssize_t i = 0; i < n; ++i)
      if (buffer[i] == '\n') out.push_back(now);
  }
  return out;
}

// The shared motions (the lead's real data), or "" when absent.
std::string shared_motions() {
  const char* dir = std::getenv("MOSTYLE_SHARED_MOTIONS_DIR");
  const std::string d = dir != nullptr ? dir : MOSTYLE_SHARED_MOTIONS;
  return fs::exists(d + "/cmu142_walk_happy.bvh") && fs::exists(d + "/bandai_walk_old.bvh") ? d : "";
}

// live-send (a 20 s 120 fps CMU walk, at 120 fps, waiting for two clients) -> live (the real
// styler: --neutral bandai_walk_normal --style bandai_walk_old, strength 1) -> a reading client;
// a second client reads live-send directly. A frame's latency is its arrival at live's client
// minus its arrival at live-send's (the source's send plus one loopback hop, tens of
// microseconds): the time live adds. Counters: frames sent and served, the share served within
// 8.3 ms, p50 / p99 / max in microseconds. One iteration of 20 s.
void BM_LiveSendReplay(benchmark::State& state) {
  const std::string dir = shared_motions();
  if (dir.empty()) {
    state.SkipWithError("no shared motions (MOSTYLE_SHARED_MOTIONS_DIR)");
    for (auto _ : state) {
    }
    return;
  }
  const std::string tmp = (fs::temp_directory_path() / ("mostyle_live_replay_" + std::to_string(::getpid()))).string();
  fs::create_directories(tmp);
  mostyle::Clip walk = mostyle::read_bvh_file(dir + "/cmu142_walk_happy.bvh");
  const int frames = std::min(walk.frames(), static_cast<int>(std::lround(20.0 * walk.fps())));
  walk.motion = mostyle::MotionMatrix(walk.motion.topRows(frames));
  const std::string take = tmp + "/walk.bvh";
  mostyle::write_bvh_file(walk, take);
  for (auto _ : state) {
    mostyle::test::CliProcess send({"live-send", take, "--serve", "0", "--clients", "2"}, tmp + "/send.err");
    const int source_port = send.port();
    mostyle::test::CliProcess live({"live", "--connect", "127.0.0.1:" + std::to_string(source_port), "--skeleton", take,
                                    "--neutral", dir + "/bandai_walk_normal.bvh", "--style",
                                    dir + "/bandai_walk_old.bvh", "--serve", "0", "--connect-timeout", "0"},
                                   tmp + "/live.err");
    const int served_port = source_port > 0 ? live.port() : -1;
    const int client = served_port > 0 ? mostyle::test::connect_local(served_port) : -1;
    // live takes its client before the first frame comes: live-send starts at its second client.
    const int direct = client >= 0 ? mostyle::test::connect_local(source_port) : -1;
    if (direct < 0) {
      state.SkipWithError(("live or live-send did not start: " + live.err() + send.err()).c_str());
      break;
    }
    std::vector<mostyle::test::TestClock::time_point> sent, served;
    std::thread source_reader([&] { sent = arrivals(direct, static_cast<size_t>(frames)); });
    served = arrivals(client, static_cast<size_t>(frames));
    source_reader.join();
    std::vector<double> us;
    for (size_t k = 0; k < std::min(sent.size(), served.size()); ++k)
      us.push_back(std::chrono::duration<double, std::micro>(served[k] - sent[k]).count());
    const double within = static_cast<double>(std::count_if(us.begin(), us.end(), [](double t) { return t <= 8333.0; }));
    state.counters["frames_sent"] = static_cast<double>(sent.size());
    state.counters["frames_served"] = static_cast<double>(served.size());
    state.counters["within_8_3ms"] = served.empty() ? 0.0 : within / static_cast<double>(frames);
    report_percentiles(state, us);
    // The iteration's time: from the first frame sent to the last served.
    state.SetIterationTime(sent.empty() || served.empty()
                               ? 0.0
                               : std::chrono::duration<double>(served.back() - sent.front()).count());
    for (int fd : {client, direct}) ::close(fd);
    live.wait();
    send.wait();
  }
  fs::remove_all(tmp);
}
BENCHMARK(BM_LiveSendReplay)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
