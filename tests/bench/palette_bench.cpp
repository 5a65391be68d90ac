// Speed of the style palette on eight one-minute takes at 30 fps (20 major joints):
// the shared decomposition of all eight (goal: under 200 ms) and one mix for new weights, what
// a weight slider or the blend pad does (goal: under 1 ms), with the timing mixed and with the
// reference's timing; and that mix as a preview (poses, root, limb lengths) and its completion
// (speed limit, foot lock, measures) apart; and a transfer onto the reference as its own neutral
// (a style's strength slider: the root on a leash, the strides fitted), whole and as a preview.
//
// Data: the eight takes of ../shared/motions it has (Bandai and CMU, two conventions, 30 and
// 120 fps), each played slower or faster so that it lasts a minute; without ../shared, the
// four bundled CMU takes twice over.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "engine/io/bvh/bvh_read.h"
#include "engine/synthesize/mix_palette.h"

namespace {

using namespace mostyle;

constexpr double kSeconds = 1799.0 / 30.0;  // 1800 frames at 30 fps

std::shared_ptr<const Clip> minute_take(const std::string& path) {
  Clip clip = read_bvh_file(path);
  clip.frame_time = kSeconds / (clip.frames() - 1);
  return std::make_shared<const Clip>(std::move(clip));
}

std::vector<std::shared_ptr<const Clip>> eight_takes() {
  const std::string shared = MOSTYLE_SHARED_MOTIONS;
  std::vector<std::string> names;
  if (std::filesystem::exists(shared + "/bandai_walk_normal.bvh")) {
    for (const char* n : {"bandai_walk_normal.bvh", "bandai_walk_old.bvh", "cmu142_walk_happy.bvh",
                          "bandai_walk_proud.bvh", "cmu142_walk_marching.bvh", "bandai_walk_tired.bvh",
                          "bandai_walk_sad.bvh", "cmu142_walk_joy.bvh"})
      names.push_back(shared + "/" + n);
  } else {
    const std::string assets = std::string(MOSTYLE_ASSETS_DIR) + "/motions/";
    for (int twice = 0; twice < 2; ++twice)
      for (const char* n : {"cmu142_walk_happy.bvh", "cmu142_walk_marching.bvh", "cmu142_walk_joy.bvh",
                            "cmu142_walk_clumsy.bvh"})
        names.push_back(assets + n);
  }
  std::vector<std::shared_ptr<const Clip>> clips;
  for (const std::string& n : names) clips.push_back(minute_take(n));
  return clips;
}

DecomposeParams bench_params() {
  DecomposeParams d;
  d.components = 10;
  return d;
}

const PreparedTakes& palette() {
  static const auto p = prepare_takes(eight_takes(), {});
  return *p;
}

const Decomposed& decomposition() {
  static const auto d = decompose_takes(palette(), bench_params());
  return *d;
}

void BM_PrepareEightTakes(benchmark::State& state) {
  const auto clips = eight_takes();
  for (auto _ : state) benchmark::DoNotOptimize(prepare_takes(clips, {}));
  state.counters["samples"] = palette().samples();
}
BENCHMARK(BM_PrepareEightTakes)->Unit(benchmark::kMillisecond)->Iterations(2);

void BM_DecomposeEightTakes(benchmark::State& state) {
  const PreparedTakes& p = palette();
  for (auto _ : state) benchmark::DoNotOptimize(decompose_takes(p, bench_params()));
  state.counters["frames"] = double(p.samples()) * p.size();
}
BENCHMARK(BM_DecomposeEightTakes)->Unit(benchmark::kMillisecond)->Iterations(3);

// A new weight set every iteration (as a drag on the blend pad gives), the whole slider path:
// poses, timing, root, limb lengths and foot lock.
// keyed: the weights keyed in time instead: from the reference's alone at 5 s to the
// weights of the move at 40 s, a new set of keys every iteration.
// stage: the whole mix, its preview only (MixParams::preview), or the preview untimed and its
// completion (finish_mix_palette) timed: what the editor shows at once and what follows.
// own_transfer: a transfer whose content (the reference) is its own neutral, one style at strength
// t: its root on the content's path (the leash) and the strides fitted to it, on the content's
// timing, as the editor's pair transfer and `transfer C --style S` run.
enum class Stage { kWhole, kPreview, kRest };
void mix_bench(benchmark::State& state, bool reference_timing, bool keyed = false, Stage stage = Stage::kWhole,
               bool own_transfer = false) {
  const PreparedTakes& p = palette();
  const Decomposed& d = decomposition();
  MixParams params;
  params.reference_timing = reference_timing;
  params.preview = stage != Stage::kWhole;
  MixScratch scratch;
  MixResult out;
  StageTimes times;
  int step = 0;
  for (auto _ : state) {
    const double t = (step++ % 16) / 16.0;
    std::vector<double> weights(p.size(), (1.0 - t) / (p.size() - 1));
    weights[step % p.size()] = t;
    double sum = 0;
    for (double w : weights) sum += w;
    weights[0] += 1.0 - sum;
    params.layers = take_layers(weights);
    if (own_transfer) {  // the content's layer, one style added from it at t
      params.layers = MixLayers{{MixLayer{0, 1.0, {}}}, {AdditiveLayer{1 + step % (p.size() - 1), 0, t, {}}}};
      params.reference_timing = true;
      params.feet_of_reference = true;
      params.reference_cycles = true;
      params.path_leash = transfer_path_leash(TransferNeutral::kContent, false);
    }
    if (keyed) {
      std::vector<double> first(p.size(), 0.0);
      first[0] = 1.0;
      params.keys = {{5.0, first}, {40.0, take_weights(params.layers, p.size())}};
    }
    if (stage == Stage::kRest) {
      state.PauseTiming();
      mix_palette(p, d, params, scratch, out, &times);
      state.ResumeTiming();
      finish_mix_palette(p, params, scratch, out, &times);
    } else {
      mix_palette(p, d, params, scratch, out, &times);
    }
    benchmark::DoNotOptimize(out.motion.world.data());
  }
  state.counters["output_frames"] = double(out.motion.world.rows());
  state.counters["synthesize_ms"] = times.synthesize_ms;
  state.counters["postprocess_ms"] = times.postprocess_ms;
}
void BM_MixEightTakes(benchmark::State& state) { mix_bench(state, false); }
void BM_MixEightTakesReferenceTiming(benchmark::State& state) { mix_bench(state, true); }
void BM_MixEightTakesKeyed(benchmark::State& state) { mix_bench(state, false, true); }
void BM_MixEightTakesPreview(benchmark::State& state) { mix_bench(state, false, false, Stage::kPreview); }
void BM_FinishEightTakesAfterPreview(benchmark::State& state) { mix_bench(state, false, false, Stage::kRest); }
void BM_OwnTransferPreview(benchmark::State& state) { mix_bench(state, true, false, Stage::kPreview, true); }
void BM_OwnTransfer(benchmark::State& state) { mix_bench(state, true, false, Stage::kWhole, true); }
BENCHMARK(BM_MixEightTakes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_OwnTransferPreview)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_OwnTransfer)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MixEightTakesPreview)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FinishEightTakesAfterPreview)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MixEightTakesKeyed)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MixEightTakesReferenceTiming)->Unit(benchmark::kMicrosecond);

}  // namespace
