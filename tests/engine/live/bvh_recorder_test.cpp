// The BVH recorder: after every frame the file reads as a whole BVH file with the frames so far;
// frame lines never cross a page; and a recorder killed with SIGKILL at random moments leaves a
// file that our reader loads whole and that Blender's importer would (every line after Frame
// Time holds all the channels as numbers).
#include "engine/live/bvh_recorder.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "engine/base/atomic_file.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/io/bvh/bvh_write.h"
#include "engine/base/error.h"
#include "tests/engine/skeleton_builder.h"
#include "tests/engine/small_bvh.h"

using namespace mostyle;
namespace fs = std::filesystem;

namespace {

// A line longer than a page is written with 7 significant digits: within this, relative.
constexpr double kShortLine = 1e-6;

class Folder {
 public:
  Folder() : dir_(fs::temp_directory_path() / ("mostyle_recorder_test_" + std::to_string(::getpid()))) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  ~Folder() { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  int files() const {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir_)) n += e.is_regular_file();
    return n;
  }

 private:
  fs::path dir_;
};

// An Axis-sized skeleton: 59 joints, 6 channels each (Axis's "displacement" output): frame lines
// of 3 to 6 KB (the longer ones written with 7 digits to fit in a page), so that lines often
// meet a page's end.
Skeleton axis_sized_skeleton() {
  test::SkeletonBuilder b;
  b.joint("Hips", "", 0, 100, 0);
  for (int i = 1; i < 59; ++i) b.joint("J" + std::to_string(i), i == 1 ? "Hips" : "J" + std::to_string(i - 1), 0, 2, 0);
  Skeleton s = b.skeleton();
  for (Joint& j : s.joints) j.channels = {Channel::kXposition, Channel::kYposition, Channel::kZposition,
                                          Channel::kZrotation, Channel::kXrotation, Channel::kYrotation};
  s.channel_count = 0;
  for (Joint& j : s.joints) {
    j.first_channel = s.channel_count;
    s.channel_count += 6;
  }
  return s;
}

// Frame f's values: distinct, of varied lengths, exact in their shortest text.
std::vector<double> frame_values(int f, int channels) {
  std::vector<double> v(static_cast<size_t>(channels));
  for (int c = 0; c < channels; ++c) v[static_cast<size_t>(c)] = f * 1000.0 + c + (c % 3 == 0 ? 0.123456789 : 0.5);
  return v;
}

// What Blender's importer needs of the frames (io_anim_bvh, read_bvh): every non-blank line after
// "Frame Time" split on whitespace has at least the channels, each a float; it ignores the count.
// Returns the number of frame lines, or -1 when Blender would fail.
int blender_frames(const std::string& text, int channels) {
  std::istringstream in(text);
  std::string line;
  bool motion = false;
  int frames = 0;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string x; words >> x;) w.push_back(x);
    if (w.empty()) continue;
    if (!motion) {
      motion = w.size() == 3 && w[0] == "Frame" && w[1] == "Time:";
      continue;
    }
    if (static_cast<int>(w.size()) < channels) return -1;
    for (const std::string& x : w) {
      try {
        size_t used = 0;
        std::stod(x, &used);
        if (used != x.size()) return -1;
      } catch (...) {
        return -1;
      }
    }
    ++frames;
  }
  return motion ? frames : -1;
}

// The header's frame count, as three.js reads it.
long long declared_frames(const std::string& text) {
  const size_t at = text.find("Frames:");
  return at == std::string::npos ? -1 : std::stoll(text.substr(at + 7));
}

}  // namespace

TEST_CASE("recorder: after each frame the file is a whole BVH file with the frames so far", "[recorder]") {
  Folder folder;
  const Clip small = parse_bvh(test::kSmallBvh, "small.bvh");
  const std::string path = folder.path("rec.bvh");
  {
    BvhRecorder r(path, small.skeleton, small.frame_time);
    CHECK_FALSE(fs::exists(path));  // not before the first frame
    for (int f = 0; f < 20; ++f) {
      const std::vector<double> v = frame_values(f, small.skeleton.channel_count);
      r.append(v.data());
      std::vector<std::string> warnings;
      const Clip back = read_bvh_file(path, &warnings);
      INFO("frame " << f);
      CHECK(warnings.empty());
      REQUIRE(back.frames() == f + 1);
      CHECK(back.frame_time == small.frame_time);
      CHECK(format_bvh_hierarchy(back.skeleton) == format_bvh_hierarchy(small.skeleton));
      for (int g = 0; g <= f; ++g)
        for (int c = 0; c < small.skeleton.channel_count; ++c)
          REQUIRE(back.motion(g, c) == frame_values(g, small.skeleton.channel_count)[static_cast<size_t>(c)]);
      CHECK(blender_frames(read_file(path), small.skeleton.channel_count) == f + 1);
      CHECK(declared_frames(read_file(path)) == f + 1);
    }
    CHECK(r.frames() == 20);
  }
  // Closed: the last line ended, nothing else left beside it.
  const std::string text = read_file(path);
  CHECK(text.back() == '\n');
  CHECK(text.find("Frames: 000000020\n") != std::string::npos);
  CHECK(folder.files() == 1);
}

TEST_CASE("recorder: no frame, no file; an unwritable folder is refused in one sentence", "[recorder]") {
  Folder folder;
  const Clip small = parse_bvh(test::kSmallBvh, "small.bvh");
  { BvhRecorder r(folder.path("none.bvh"), small.skeleton, small.frame_time); }
  CHECK(folder.files() == 0);
  const std::string bad = folder.path("missing/rec.bvh");
  try {
    BvhRecorder r(bad, small.skeleton, small.frame_time);
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) == bad + ": cannot write: No such file or directory");
  }
}

TEST_CASE("recorder: frame lines stay within a page, the count's digits too", "[recorder]") {
  Folder folder;
  const Skeleton skeleton = axis_sized_skeleton();
  const long page = ::sysconf(_SC_PAGESIZE);
  // Names lengthened until the count's nine digits would cross a page: they are moved past it.
  Skeleton padded = skeleton;
  bool crossed = false;
  for (long extra = 0; extra <= page && !crossed; ++extra) {
    padded.joints[0].name = "Hips" + std::string(static_cast<size_t>(extra), 'x');
    const size_t digits = format_bvh_hierarchy(padded).size() + std::string("MOTION\nFrames: ").size();
    crossed = digits / page != (digits + 8) / page;
  }
  REQUIRE(crossed);
  for (const Skeleton& s : {skeleton, padded}) {
    const std::string path = folder.path("pages.bvh");
    {
      BvhRecorder r(path, s, 1.0 / 60.0);
      for (int f = 0; f < 40; ++f) r.append(frame_values(f, s.channel_count).data());
    }
    const std::string text = read_file(path);
    const size_t digits = text.find("Frames:") + 7;
    const size_t first = text.find_first_not_of(' ', digits);
    CHECK(text.substr(first, 9) == "000000040");
    CHECK(first / page == (first + 8) / page);
    // Every frame after the first: its line end before it and its values in one page.
    size_t at = text.find('\n', text.find("Frame Time:"));
    at = text.find('\n', at + 1);  // the second frame starts here
    int lines = 0;
    while (at + 1 < text.size()) {
      const size_t end = text.find('\n', at + 1);
      const size_t last = (end == std::string::npos ? text.size() : end) - 1;
      const size_t values_end = text.find_last_not_of(' ', last);
      CHECK(at / page == values_end / page);
      ++lines;
      at = end == std::string::npos ? text.size() : end;
    }
    CHECK(lines == 39);
    std::vector<std::string> warnings;
    CHECK(read_bvh_file(path, &warnings).frames() == 40);
    CHECK(warnings.empty());
  }
}

TEST_CASE("recorder: killed with SIGKILL at random moments, the file reads whole", "[recorder]") {
  Folder folder;
  const Skeleton skeleton = axis_sized_skeleton();
  const int channels = skeleton.channel_count;
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> wait_us(1000, 10000);
  int killed_with_frames = 0;
  for (int trial = 0; trial < 30; ++trial) {
    const std::string path = folder.path("killed" + std::to_string(trial) + ".bvh");
    // Frames made before fork: the child only appends.
    std::vector<std::vector<double>> frames;
    for (int f = 0; f < 2000; ++f) frames.push_back(frame_values(f, channels));
    const pid_t child = ::fork();
    if (child == 0) {
      try {
        BvhRecorder r(path, skeleton, 1.0 / 120.0);
        for (;;)
          for (const auto& v : frames) r.append(v.data());
      } catch (...) {
      }
      ::_exit(1);
    }
    // Killed at a random moment once the recording has begun (its file appears with its first
    // frame): a loaded machine, or a sanitizer build, may take longer than the wait to get there.
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!fs::exists(path) && std::chrono::steady_clock::now() < give_up)
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    std::this_thread::sleep_for(std::chrono::microseconds(wait_us(rng)));
    ::kill(child, SIGKILL);
    int status = 0;
    ::waitpid(child, &status, 0);
    REQUIRE(WIFSIGNALED(status));
    INFO("trial " << trial);
    if (!fs::exists(path)) continue;  // killed before its first frame: no file
    ++killed_with_frames;
    const std::string text = read_file(path);
    const int lines = blender_frames(text, channels);
    CHECK(lines >= 1);
    const long long declared = declared_frames(text);
    CHECK((declared == lines || declared == lines - 1));
    std::vector<std::string> warnings;
    const Clip back = parse_bvh(text, path, &warnings);
    CHECK(back.frames() == lines);
    CHECK(warnings.size() <= 1);  // at most "Frames: says n - 1"
    for (int f = 0; f < back.frames(); ++f)
      for (int c = 0; c < channels; c += 37) {
        const double expected = frames[static_cast<size_t>(f % 2000)][static_cast<size_t>(c)];
        REQUIRE(std::abs(back.motion(f, c) - expected) <= kShortLine * std::abs(expected));
      }
    fs::remove(path);
  }
  // Every kill comes after the first frame.
  CHECK(killed_with_frames == 30);
}
