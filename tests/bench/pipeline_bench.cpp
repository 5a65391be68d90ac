// Speed of the pair pipeline on a minute of motion at 30 fps (1800 frames, 20 major joints):
// prepare_takes of two takes (resample, FK, retarget, canonical frame, DTW), decompose_takes (shared mode, k = 10)
// and a blend (the mix of two, mix_layers.h) for one alpha, the slider move, which must stay well under 1 ms. With the timing
// blended the output's length changes with alpha, and its buffers are resized then (the
// allocations are counted here by wrapping malloc); with A's timing it allocates nothing once
// its scratch has the right size.
//
// Data: two CMU takes from ../shared/motions (marching and happy, 27 s and 25 s at 120 fps)
// played slower so that each lasts a minute, then resampled to 30 fps by the pipeline: 1800 frames.
// Without ../shared, the bundled 9 s takes, slowed down the same way.
#include <benchmark/benchmark.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "tests/engine/worker/blend_at.h"
#include "engine/io/bvh/bvh_read.h"

// Every heap allocation of the process goes through these (glibc lets a program replace them;
// the __libc_ functions are glibc's own), so the blend benchmark can count them.
extern "C" {
void* __libc_malloc(size_t size);
void* __libc_calloc(size_t count, size_t size);
void* __libc_realloc(void* p, size_t size);
void __libc_free(void* p);
}
namespace {
std::atomic<long> g_allocations{0};
}
extern "C" {
void* malloc(size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
void* calloc(size_t count, size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(count, size);
}
void* realloc(void* p, size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(p, size);
}
void free(void* p) { __libc_free(p); }
}

namespace {

using namespace mostyle;

constexpr double kSeconds = 1799.0 / 30.0;  // the take's duration after slowing down: 1800 frames at 30 fps

// The clip played slower so that it lasts kSeconds (its frame time stretched).
std::shared_ptr<const Clip> minute_take(const std::string& name) {
  const std::string shared = std::string(MOSTYLE_SHARED_MOTIONS) + "/" + name;
  const std::string path = std::filesystem::exists(shared) ? shared : std::string(MOSTYLE_ASSETS_DIR) + "/motions/" + name;
  Clip clip = read_bvh_file(path);
  clip.frame_time = kSeconds / (clip.frames() - 1);
  return std::make_shared<const Clip>(std::move(clip));
}

struct Pair {
  std::shared_ptr<const PreparedTakes> prepared;
  std::shared_ptr<const Decomposed> decomposed;
};

DecomposeParams bench_params() {
  DecomposeParams d;
  d.components = 10;
  return d;  // sparsity 0.5, at most 100 iterations
}

const Pair& minute_pair() {
  static const Pair pair = [] {
    Pair p;
    p.prepared = prepare_takes({minute_take("cmu142_walk_marching.bvh"), minute_take("cmu142_walk_happy.bvh")}, {});
    p.decomposed = decompose_takes(*p.prepared, bench_params());
    return p;
  }();
  return pair;
}

void BM_PreparePair(benchmark::State& state) {
  const auto a = minute_take("cmu142_walk_marching.bvh");
  const auto b = minute_take("cmu142_walk_happy.bvh");
  std::shared_ptr<const PreparedTakes> p;
  StageTimes times;
  for (auto _ : state) {
    p = prepare_takes({a, b}, {}, nullptr, &times);
    benchmark::DoNotOptimize(p.get());
  }
  state.counters["frames"] = static_cast<double>(p->reference().world.rows());
  state.counters["joints"] = static_cast<double>(p->majors.size());
  state.counters["dtw_ms"] = times.dtw_ms;
}
BENCHMARK(BM_PreparePair)->Unit(benchmark::kMillisecond);

// Cycle detection of both takes and the registration by cycles of a pair of one-minute
// walks at their own cadence (the 27 s and 25 s takes played twice and more over, not slowed):
// what prepare_takes adds to the whole-take path, measured apart from FK and retargeting.
std::shared_ptr<const Clip> repeated_minute_take(const std::string& name) {
  const std::string shared = std::string(MOSTYLE_SHARED_MOTIONS) + "/" + name;
  const std::string path = std::filesystem::exists(shared) ? shared : std::string(MOSTYLE_ASSETS_DIR) + "/motions/" + name;
  Clip clip = read_bvh_file(path);
  const int frames = static_cast<int>(std::ceil(60.0 * clip.fps()));
  Eigen::MatrixXd motion(frames, clip.motion.cols());
  for (int f = 0; f < frames; ++f) motion.row(f) = clip.motion.row(f % clip.frames());
  clip.motion = motion;
  return std::make_shared<const Clip>(std::move(clip));
}

void BM_CyclesAndRegistrationPair(benchmark::State& state) {
  PrepareOptions whole;  // the takes as they are, their own canonical frames kept
  whole.align.time_base = TimeBase::kWhole;
  static const auto p = prepare_takes(
      {repeated_minute_take("cmu142_walk_marching.bvh"), repeated_minute_take("cmu142_walk_happy.bvh")}, whole);
  const PreparedTake& a = p->takes[0];
  const PreparedTake& b = p->takes[1];
  AlignmentOptions options;
  size_t cycles = 0;
  for (auto _ : state) {
    const TakeCycles ca = detect_cycles(a.own_contacts, a.canonical.local, p->fps, p->feet.leg_length);
    CycleOptions at_foot;
    at_foot.foot = ca.foot;
    const TakeCycles cb = detect_cycles(b.own_contacts, b.canonical.local, p->fps, p->feet.leg_length, at_foot);
    const int fade = std::max(2, static_cast<int>(std::lround(0.5 * ca.period)));
    const RegisteredMotion r = register_by_cycles(a.canonical, a.own_contacts, ca, b.canonical, b.own_contacts, cb, fade);
    const Alignment al = align_by_cycles(a.canonical, r, p->feature_joints, p->feet.leg_length, p->fps, options);
    benchmark::DoNotOptimize(al.warp.a.data());
    cycles = ca.cycles.size();
  }
  state.counters["frames"] = static_cast<double>(a.canonical.local.rows());
  state.counters["cycles"] = static_cast<double>(cycles);
}
BENCHMARK(BM_CyclesAndRegistrationPair)->Unit(benchmark::kMillisecond);

void BM_DecomposePair(benchmark::State& state) {
  const PreparedTakes& p = *minute_pair().prepared;
  std::shared_ptr<const Decomposed> d;
  for (auto _ : state) {
    d = decompose_takes(p, bench_params());
    benchmark::DoNotOptimize(d.get());
  }
  state.counters["frames"] = static_cast<double>(p.reference().x.rows());
  state.counters["k"] = d->components();
  state.counters["iterations"] = d->iterations;
}
BENCHMARK(BM_DecomposePair)->Unit(benchmark::kMillisecond);

// One slider move. Arg 0: everything (synthesis, timing, root, limb lengths, foot lock); 1: no
// foot lock; 2: no foot lock and no limb lengths; 3: everything on A's timeline (--timing a);
// 4: everything and a seamless loop cut.
void BM_BlendPair(benchmark::State& state) {
  const Pair& pair = minute_pair();
  MixParams params;
  params.finish.foot_lock = state.range(0) < 1 || state.range(0) >= 3;
  params.finish.limb_lengths = state.range(0) < 2 || state.range(0) >= 3;
  params.reference_timing = state.range(0) == 3;
  params.finish.loop = state.range(0) == 4;
  test::BlendRun scratch;
  MixResult out;
  test::blend_into(*pair.prepared, *pair.decomposed, 0.5, params, scratch, out);  // sizes the scratch
  const long before = g_allocations.load();
  double synthesize_ms = 0, postprocess_ms = 0;
  StageTimes times;
  int step = 0;
  for (auto _ : state) {
    test::blend_into(*pair.prepared, *pair.decomposed, 0.01 * (step++ % 101), params, scratch, out, &times);
    benchmark::DoNotOptimize(out.motion.world.data());
    synthesize_ms += times.synthesize_ms;
    postprocess_ms += times.postprocess_ms;
  }
  const long allocations = g_allocations.load() - before;
  if (allocations != 0 && params.reference_timing) state.SkipWithError("the blend allocated with a sized scratch");
  state.counters["allocations_per_move"] = static_cast<double>(allocations) / std::max(1, step);
  state.counters["frames"] = static_cast<double>(out.motion.world.rows());
  state.counters["synthesize_ms"] = synthesize_ms / std::max(1, step);
  state.counters["postprocess_ms"] = postprocess_ms / std::max(1, step);
}
BENCHMARK(BM_BlendPair)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Arg(4)->Unit(benchmark::kMicrosecond);

// Per-component alphas (each component its own): one 2k x 3N mixing matrix is allocated.
void BM_BlendPairComponentAlphas(benchmark::State& state) {
  const Pair& pair = minute_pair();
  const std::vector<double> alphas(pair.decomposed->components(), 0.3);
  test::BlendRun scratch;
  MixResult out;
  const MixParams params;
  test::blend_into(*pair.prepared, *pair.decomposed, 0.5, params, scratch, out, nullptr, alphas);
  for (auto _ : state) {
    test::blend_into(*pair.prepared, *pair.decomposed, 0.5, params, scratch, out, nullptr, alphas);
    benchmark::DoNotOptimize(out.motion.world.data());
  }
}
BENCHMARK(BM_BlendPairComponentAlphas)->Unit(benchmark::kMicrosecond);

}  // namespace
