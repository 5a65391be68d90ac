// BVH parse speed in MB/s (SetBytesProcessed): the CMU files read once into memory and parsed
// repeatedly, the Bandai files likewise, and a synthetic 100 MB file; plus the writer and FK.
// For scale: three.js's loader reads about 14 MB/s, Blender's importer about 2.4 MB/s.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/io/atomic_file.h"
#include "engine/io/bvh_io.h"
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
