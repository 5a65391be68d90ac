// Speed of export and foot lock: the rotation solve of a real blend onto A's full skeleton
// (an export click; target: well under a second for a minute of motion), and a blend (the mix of two, mix_layers.h) with
// the foot lock (a slider move; target: synthesis and post-processing of a minute at 30 fps
// well under 1 ms), the lock alone, and contact detection (once per pair).
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "tests/engine/worker/blend_at.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/base/error.h"
#include "engine/export/export_solve.h"
#include "engine/post/foot_lock.h"

namespace {

const std::string kAssets = MOSTYLE_ASSETS_DIR;
const std::string kShared = MOSTYLE_SHARED_MOTIONS;

struct Pair {
  std::shared_ptr<const mostyle::PreparedTakes> prepared;
  std::shared_ptr<const mostyle::Decomposed> decomposed;
  mostyle::MixResult blend;
};

// A prepared, decomposed and blended pair; `ok` false when the files are absent.
Pair load_pair(const std::string& a, const std::string& b, bool* ok) {
  Pair p;
  *ok = false;
  try {
    auto clip_a = std::make_shared<const mostyle::Clip>(mostyle::read_bvh_file(a));
    auto clip_b = std::make_shared<const mostyle::Clip>(mostyle::read_bvh_file(b));
    p.prepared = mostyle::prepare_takes({clip_a, clip_b}, mostyle::PrepareOptions{});
  } catch (const mostyle::InputError&) {
    return p;
  }
  mostyle::DecomposeParams dp;
  dp.max_iterations = 30;
  p.decomposed = mostyle::decompose_takes(*p.prepared, dp);
  mostyle::test::BlendRun scratch;
  mostyle::test::blend_into(*p.prepared, *p.decomposed, 0.5, mostyle::MixParams(), scratch, p.blend);
  *ok = true;
  return p;
}

// CMU 142 happy with joy from ../shared/motions: 25 s (759 frames at 30 fps) of a 31-joint skeleton
// with fingers; the bundled 9 s versions when the shared folder is absent.
Pair cmu_pair(bool* ok) {
  Pair p = load_pair(kShared + "/cmu142_walk_happy.bvh", kShared + "/cmu142_walk_joy.bvh", ok);
  if (!*ok) p = load_pair(kAssets + "/motions/cmu142_walk_happy.bvh", kAssets + "/motions/cmu142_walk_joy.bvh", ok);
  return p;
}

void BM_ExportSolveCmu(benchmark::State& state) {
  bool ok = false;
  const Pair p = cmu_pair(&ok);
  if (!ok) return state.SkipWithError("no CMU motions");
  for (auto _ : state) {
    const mostyle::ExportResult r = mostyle::solve_export_at(*p.prepared->reference().clip, mostyle::export_joints(*p.prepared), p.blend.motion.world, mostyle::source_frames_in_clip(*p.prepared, p.blend), p.prepared->fps);
    benchmark::DoNotOptimize(r.clip.motion.data());
  }
  state.counters["frames"] = static_cast<double>(p.blend.motion.world.rows());
}
BENCHMARK(BM_ExportSolveCmu)->Unit(benchmark::kMillisecond);

// Bandai as A: a rigid pelvis and clavicles, so the hips' and chest's fits iterate.
void BM_ExportSolveBandai(benchmark::State& state) {
  bool ok = false;
  const Pair p = load_pair(kShared + "/bandai_walk_normal.bvh", kShared + "/bandai_walk_tired.bvh", &ok);
  if (!ok) return state.SkipWithError("../shared/motions is absent");
  for (auto _ : state) {
    const mostyle::ExportResult r = mostyle::solve_export_at(*p.prepared->reference().clip, mostyle::export_joints(*p.prepared), p.blend.motion.world, mostyle::source_frames_in_clip(*p.prepared, p.blend), p.prepared->fps);
    benchmark::DoNotOptimize(r.clip.motion.data());
  }
  state.counters["frames"] = static_cast<double>(p.blend.motion.world.rows());
}
BENCHMARK(BM_ExportSolveBandai)->Unit(benchmark::kMillisecond);

// A slider move with the foot lock on: synthesis and post-processing, no allocation.
void BM_BlendWithFootLock(benchmark::State& state) {
  bool ok = false;
  const Pair p = cmu_pair(&ok);
  if (!ok) return state.SkipWithError("no CMU motions");
  mostyle::MixParams params;
  params.finish.foot_lock = state.range(0) != 0;
  mostyle::test::BlendRun scratch;
  mostyle::MixResult out;
  double alpha = 0.0;
  for (auto _ : state) {
    mostyle::test::blend_into(*p.prepared, *p.decomposed, alpha, params, scratch, out);
    benchmark::DoNotOptimize(out.motion.world.data());
    alpha = alpha > 1.0 ? 0.0 : alpha + 0.01;
  }
  state.counters["frames"] = static_cast<double>(out.motion.world.rows());
}
BENCHMARK(BM_BlendWithFootLock)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// The foot lock alone on a minute of 30 fps motion (the pair's blend tiled to 1800 frames).
void BM_FootLockMinute(benchmark::State& state) {
  bool ok = false;
  const Pair p = cmu_pair(&ok);
  if (!ok) return state.SkipWithError("no CMU motions");
  const Eigen::Index n = p.blend.motion.world.rows();
  Eigen::MatrixXd world(1800, p.blend.motion.world.cols());
  for (Eigen::Index f = 0; f < 1800; ++f) world.row(f) = p.blend.motion.world.row(f % n);
  mostyle::FootLockScratch scratch;
  Eigen::MatrixXd work = world;
  for (auto _ : state) {
    work = world;
    mostyle::apply_foot_lock(work, p.prepared->feet, scratch);
    benchmark::DoNotOptimize(work.data());
  }
}
BENCHMARK(BM_FootLockMinute)->Unit(benchmark::kMicrosecond);

void BM_DetectFootContacts(benchmark::State& state) {
  bool ok = false;
  const Pair p = cmu_pair(&ok);
  if (!ok) return state.SkipWithError("no CMU motions");
  for (auto _ : state) {
    const Eigen::MatrixXd c = mostyle::detect_foot_contacts(p.prepared->reference().world, p.prepared->feet);
    benchmark::DoNotOptimize(c.data());
  }
}
BENCHMARK(BM_DetectFootContacts)->Unit(benchmark::kMicrosecond);

}  // namespace
