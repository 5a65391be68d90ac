// The live styler's time per stream frame on one core (LiveStyle::style_frame: FK, canonical
// frame, contacts and phase, the change, the foot lock, the rotation solve), the stream played
// on repeat so the styler keeps walking in cycles: a 59-joint Axis Neuron rig (a CMU walk put on
// it) and the 22-joint Bandai rig, styled normal -> old at strength 1 (the Bandai takes from
// ../shared/motions; without them the bundled CMU happy -> marching pair). The construction
// (preparing the takes) is timed once apart.
#include <benchmark/benchmark.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "engine/io/bvh/bvh_read.h"
#include "engine/live/live_style.h"
#include "tests/engine/live/axis_rig.h"

// Heap allocations made by this program (glibc's malloc family, which operator new and Eigen
// both call), counted so the benchmark can say how many a frame makes.
std::atomic<long> g_allocations{0};

extern "C" {
void* __libc_malloc(size_t size);
void* __libc_calloc(size_t count, size_t size);
void* __libc_realloc(void* p, size_t size);
void* __libc_memalign(size_t alignment, size_t size);
void* malloc(size_t size) {
  ++g_allocations;
  return __libc_malloc(size);
}
void* calloc(size_t count, size_t size) {
  ++g_allocations;
  return __libc_calloc(count, size);
}
void* realloc(void* p, size_t size) {
  ++g_allocations;
  return __libc_realloc(p, size);
}
void* aligned_alloc(size_t alignment, size_t size) {
  ++g_allocations;
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** p, size_t alignment, size_t size) {
  ++g_allocations;
  *p = __libc_memalign(alignment, size);
  return *p != nullptr ? 0 : 12;  // ENOMEM
}
}

namespace {

namespace fs = std::filesystem;
using mostyle::Clip;

std::string shared(const std::string& name) {
  const char* dir = std::getenv("MOSTYLE_SHARED_MOTIONS_DIR");
  const fs::path p = fs::path(dir != nullptr ? dir : MOSTYLE_SHARED_MOTIONS) / name;
  std::error_code ec;
  return fs::exists(p, ec) ? p.string() : std::string();
}

std::shared_ptr<const Clip> load(const std::string& path) {
  return std::make_shared<const Clip>(mostyle::read_bvh_file(path));
}

// [neutral, style]: Bandai normal and old, or the bundled CMU happy and marching.
std::vector<std::shared_ptr<const Clip>> takes() {
  const std::string normal = shared("bandai_walk_normal.bvh"), old = shared("bandai_walk_old.bvh");
  if (!normal.empty() && !old.empty()) return {load(normal), load(old)};
  const fs::path assets = fs::path(MOSTYLE_ASSETS_DIR) / "motions";
  return {load((assets / "cmu142_walk_happy.bvh").string()), load((assets / "cmu142_walk_marching.bvh").string())};
}

void style_frames(benchmark::State& state, const Clip& stream) {
  const long before = g_allocations.load();
  const auto t0 = std::chrono::steady_clock::now();
  mostyle::LiveStyle live(stream.skeleton, stream.fps(), {takes(), {1.0}});
  const double setup_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const long allocations_setup = g_allocations.load() - before;
  mostyle::MotionMatrix out(1, stream.skeleton.channel_count);
  // Warm-up: one pass over the stream, then the allocations of the timed frames are counted.
  for (int w = 0; w < stream.frames(); ++w) live.style_frame(stream.motion.row(w).data(), out.data());
  const long allocations = g_allocations.load();
  int f = 0;
  for (auto _ : state) {
    live.style_frame(stream.motion.row(f).data(), out.data());
    benchmark::DoNotOptimize(out.data());
    f = (f + 1) % stream.frames();
  }
  state.counters["allocations_per_frame"] = double(g_allocations.load() - allocations) / double(state.iterations());
  state.counters["joints"] = stream.skeleton.joint_count_without_end_sites();
  state.counters["setup_ms"] = setup_ms;
  state.counters["setup_allocations"] = double(allocations_setup);
  state.counters["in_cycle"] = live.in_cycle() ? 1 : 0;
  state.SetItemsProcessed(state.iterations());  // frames
}

void BM_LiveStyleFrame_Axis59(benchmark::State& state) {
  const Clip source = mostyle::read_bvh_file((fs::path(MOSTYLE_ASSETS_DIR) / "motions" / "cmu142_walk_joy.bvh").string());
  static const Clip stream = mostyle::test::on_axis_rig(source);
  style_frames(state, stream);
}
BENCHMARK(BM_LiveStyleFrame_Axis59)->Unit(benchmark::kMicrosecond);

void BM_LiveStyleFrame_Bandai22(benchmark::State& state) {
  const std::string path = shared("bandai_walk_proud.bvh");
  if (path.empty()) {
    state.SkipWithError("../shared/motions is absent: no Bandai take");
    return;
  }
  static const Clip stream = mostyle::read_bvh_file(path);
  style_frames(state, stream);
}
BENCHMARK(BM_LiveStyleFrame_Bandai22)->Unit(benchmark::kMicrosecond);

}  // namespace
