// `mostyle-cli info` reads a take and finds its cycles: reading a long BVH against reading it and
// finding its cycles (take_cycles: FK of the hips and legs, contacts, canonical frame, cycles),
// take_cycles alone, and, for scale, what it replaced: preparing the take as a pair with itself
// (retargeting, both takes' cycles, an alignment) to read the reference's cycles. The take is CMU's 22 s joyful walk at 120 fps from ../shared/motions, or
// when that is absent a bundled CMU take repeated to a minute.
#include <benchmark/benchmark.h>
#include <malloc.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <unistd.h>

#include "engine/base/atomic_file.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/io/bvh/bvh_write.h"
#include "engine/io/motion_file.h"
#include "engine/align/prepare_takes.h"

namespace {

namespace fs = std::filesystem;
using mostyle::Clip;

// The long take's path: the shared one, else a minute of a bundled take written to a temporary
// file (removed at exit).
struct LongTake {
  std::string path;
  bool written = false;
  LongTake() {
    const fs::path shared = fs::path(MOSTYLE_SHARED_MOTIONS) / "cmu142_walk_joy.bvh";
    std::error_code ec;
    if (fs::exists(shared, ec)) {
      path = shared.string();
      return;
    }
    std::string first;
    for (const auto& e : fs::directory_iterator(fs::path(MOSTYLE_ASSETS_DIR) / "motions", ec))
      if (e.path().extension() == ".bvh" && (first.empty() || e.path().string() < first)) first = e.path().string();
    const Clip source = mostyle::read_bvh_file(first);
    Clip minute = source;
    const int frames = static_cast<int>(60.0 * source.fps());
    minute.motion.resize(frames, source.motion.cols());
    for (int f = 0; f < frames; ++f) minute.motion.row(f) = source.motion.row(f % source.frames());
    path = (fs::temp_directory_path() / ("mostyle_cycles_bench_" + std::to_string(getpid()) + ".bvh")).string();
    mostyle::write_bvh_file(minute, path);
    written = true;
  }
  ~LongTake() {
    std::error_code ec;
    if (written) fs::remove(path, ec);
  }
};

const std::string& long_take() {
  // Keep freed memory in the heap: glibc would return a take's buffers to the kernel between
  // iterations and fault them in again, which a process reading one take pays once.
  static const bool heap = [] {
    mallopt(M_MMAP_THRESHOLD, 1 << 28);
    mallopt(M_TRIM_THRESHOLD, 1 << 28);
    return true;
  }();
  (void)heap;
  static const LongTake take;
  return take.path;
}

void BM_ReadLongTake(benchmark::State& state) {
  for (auto _ : state) {
    const Clip clip = mostyle::read_motion_file(long_take());
    benchmark::DoNotOptimize(clip.motion.data());
  }
  state.SetLabel(fs::path(long_take()).filename().string());
}
BENCHMARK(BM_ReadLongTake)->Unit(benchmark::kMillisecond);

void BM_ReadLongTakeAndCycles(benchmark::State& state) {
  for (auto _ : state) {
    const auto clip = std::make_shared<const Clip>(mostyle::read_motion_file(long_take()));
    const mostyle::TakeCycles cycles = mostyle::take_cycles(clip);
    benchmark::DoNotOptimize(cycles.cycles.data());
  }
  state.SetLabel(fs::path(long_take()).filename().string());
}
BENCHMARK(BM_ReadLongTakeAndCycles)->Unit(benchmark::kMillisecond);

void BM_TakeCycles(benchmark::State& state) {
  const auto clip = std::make_shared<const Clip>(mostyle::read_motion_file(long_take()));
  for (auto _ : state) {
    const mostyle::TakeCycles cycles = mostyle::take_cycles(clip);
    benchmark::DoNotOptimize(cycles.cycles.data());
  }
  state.SetLabel(std::to_string(clip->frames()) + " frames");
}
BENCHMARK(BM_TakeCycles)->Unit(benchmark::kMillisecond);

void BM_PrepareTakeAsPair(benchmark::State& state) {
  const auto clip = std::make_shared<const Clip>(mostyle::read_motion_file(long_take()));
  mostyle::PrepareOptions own_rate;
  own_rate.fps = 0.0;
  own_rate.align.time_base = mostyle::TimeBase::kWhole;
  for (auto _ : state) {
    const auto prepared = mostyle::prepare_takes({clip, clip}, own_rate);
    benchmark::DoNotOptimize(prepared->reference().cycles.cycles.data());
  }
  state.SetLabel(std::to_string(clip->frames()) + " frames");
}
BENCHMARK(BM_PrepareTakeAsPair)->Unit(benchmark::kMillisecond);

}  // namespace
