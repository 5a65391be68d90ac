// BVH parse speed in MB/s (SetBytesProcessed): the CMU files read once into memory and parsed
// repeatedly, the Bandai files likewise, and a synthetic 100 MB file; reading a pair of 22 MB
// takes from files (the aim: under 150 ms); plus the writer and FK.
// For scale: three.js's loader reads about 14 MB/s, Blender's importer about 2.4 MB/s.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "engine/base/atomic_file.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/io/bvh/bvh_write.h"
#include "engine/kinematics/kinematics.h"

namespace {

namespace fs = std::filesystem;
using mostyle::Clip;

// The texts of the .bvh files in `dir` whose names start with `prefix`.
std::vector<std::string> texts_of(const fs::path& dir, const std::string& prefix) {
  std::vector<std::string> out;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  std::vector<fs::path> paths;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) == 0 && e.path().extension() == ".bvh") paths.push_back(e.path());
  }
  std::sort(paths.begin(), paths.end());
  for (const auto& p : paths) out.push_back(mostyle::read_file(p.string()));
  return out;
}

// The full CMU takes from ../shared/motions, or the trimmed ones in assets/ when it is absent.
const std::vector<std::string>& cmu_texts() {
  static const std::vector<std::string> texts = [] {
    std::vector<std::string> t = texts_of(MOSTYLE_SHARED_MOTIONS, "cmu142_");
    return t.empty() ? texts_of(fs::path(MOSTYLE_ASSETS_DIR) / "motions", "cmu142_") : t;
  }();
  return texts;
}

const std::vector<std::string>& bandai_texts() {
  static const std::vector<std::string> texts = texts_of(MOSTYLE_SHARED_MOTIONS, "bandai_");
  return texts;
}

// A CMU take written by our writer with its frames repeated up to 100 MB.
const std::string& synthetic_100mb() {
  static const std::string text = [] {
    const Clip source = mostyle::parse_bvh(cmu_texts().front(), "cmu.bvh");
    const size_t bytes_per_frame = cmu_texts().front().size() / std::max(1, source.frames());
    const int frames = static_cast<int>(100'000'000 / bytes_per_frame) + 1;
    Clip big = source;
    big.motion.resize(frames, source.motion.cols());
    for (int f = 0; f < frames; ++f) big.motion.row(f) = source.motion.row(f % source.frames());
    std::string t = mostyle::format_bvh(big);
    return t;
  }();
  return text;
}

// The marching CMU take as its exporter wrote it (CRLF, tabs, 6 decimals), its frame lines
// repeated up to `bytes` and its Frames: line set to match: what a long real take looks like.
std::string repeated_cmu_take(size_t bytes) {
  const std::string& take = cmu_texts().back();  // cmu142_walk_marching.bvh when present
  size_t body = take.find("Frame Time:");
  body = take.find('\n', body) + 1;
  const size_t frames_at = take.find("Frames:");
  const std::string frame_lines = take.substr(body);
  std::string repeated;
  while (repeated.size() + frame_lines.size() <= bytes) repeated += frame_lines;
  for (size_t at = 0; repeated.size() < bytes;) {  // the rest, whole lines
    const size_t next = frame_lines.find('\n', at) + 1;
    repeated.append(frame_lines, at, next - at);
    at = next;
  }
  const long frames = static_cast<long>(std::count(repeated.begin(), repeated.end(), '\n'));
  return take.substr(0, frames_at) + "Frames: " + std::to_string(frames) + "\r\n" +
         take.substr(take.find("Frame Time:"), body - take.find("Frame Time:")) + repeated;
}

// Two such 22 MB takes written to the temporary folder once, removed at exit.
const std::vector<std::string>& pair_of_22mb_files() {
  struct Files {
    std::vector<std::string> paths;
    ~Files() {
      for (const std::string& p : paths) fs::remove(p);
    }
  };
  static const Files files = [] {
    Files f;
    const std::string text = repeated_cmu_take(22'000'000);
    for (const char* name : {"a", "b"}) {
      f.paths.push_back((fs::temp_directory_path() / ("mostyle_bench_22mb_" + std::to_string(::getpid()) +
                                                       "_" + name + ".bvh")).string());
      std::ofstream(f.paths.back(), std::ios::binary) << text;
    }
    return f;
  }();
  return files.paths;
}

void parse_all(benchmark::State& state, const std::vector<std::string>& texts) {
  if (texts.empty()) {
    state.SkipWithError("no input files");
    return;
  }
  size_t bytes = 0;
  for (const std::string& t : texts) bytes += t.size();
  for (auto _ : state) {
    for (const std::string& t : texts) {
      Clip clip = mostyle::parse_bvh(t, "bench.bvh");
      benchmark::DoNotOptimize(clip.motion.data());
    }
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(bytes));
}

void BM_ParseCmu(benchmark::State& state) { parse_all(state, cmu_texts()); }
BENCHMARK(BM_ParseCmu)->Unit(benchmark::kMillisecond);

void BM_ParseBandai(benchmark::State& state) { parse_all(state, bandai_texts()); }
BENCHMARK(BM_ParseBandai)->Unit(benchmark::kMillisecond);

void BM_ParseSynthetic100MB(benchmark::State& state) {
  const std::vector<std::string> one{synthetic_100mb()};
  parse_all(state, one);
}
BENCHMARK(BM_ParseSynthetic100MB)->Unit(benchmark::kMillisecond)->MinTime(3.0);

// What loading a pair of long takes costs, file reading included (page cache warm).
void BM_ReadPair22MB(benchmark::State& state) {
  if (cmu_texts().empty()) {
    state.SkipWithError("no input files");
    return;
  }
  const std::vector<std::string>& paths = pair_of_22mb_files();
  size_t bytes = 0;
  for (const std::string& p : paths) bytes += fs::file_size(p);
  for (auto _ : state) {
    for (const std::string& p : paths) {
      Clip clip = mostyle::read_bvh_file(p);
      benchmark::DoNotOptimize(clip.motion.data());
    }
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(bytes));
}
BENCHMARK(BM_ReadPair22MB)->Unit(benchmark::kMillisecond);

void BM_FormatCmu(benchmark::State& state) {
  const Clip clip = mostyle::parse_bvh(cmu_texts().front(), "cmu.bvh");
  size_t bytes = 0;
  for (auto _ : state) {
    const std::string text = mostyle::format_bvh(clip);
    bytes = text.size();
    benchmark::DoNotOptimize(text.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(bytes));
}
BENCHMARK(BM_FormatCmu)->Unit(benchmark::kMillisecond);

void BM_JointPositionsCmu(benchmark::State& state) {
  const Clip clip = mostyle::parse_bvh(cmu_texts().front(), "cmu.bvh");
  for (auto _ : state) {
    const Eigen::MatrixXd p = mostyle::joint_positions(clip);
    benchmark::DoNotOptimize(p.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * clip.frames());  // frames/s
}
BENCHMARK(BM_JointPositionsCmu)->Unit(benchmark::kMillisecond);

}  // namespace
