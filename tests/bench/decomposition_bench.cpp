// Speed of the numerical core: decomposition (targets: 1800 x 60, k = 10, f = 0.1 well under
// 50 ms; per iteration at 1000 frames far under the 5 ms of a NumPy version), one synthesis
// (well under 1 ms) and the limb-length constraint.
#include <benchmark/benchmark.h>

#include <vector>

#include "engine/decompose/decomposition.h"
#include "engine/kinematics/limb_length.h"
#include "engine/synthesize/synthesis.h"
#include "tests/engine/synthetic_motion.h"

namespace {

using mostyle::test::synthetic_motion;

// A minute of 30 fps motion of the 20 major joints.
constexpr int kFrames = 1800;
constexpr int kJoints = 20;

void BM_Decompose(benchmark::State& state) {
  const Eigen::MatrixXd x = synthetic_motion(kFrames, kJoints, 6, 0.02, 1);
  mostyle::DecompositionOptions options;  // k = 10, f = 0.1, <= 100 iterations, tol 1e-6
  int iterations = 0;
  for (auto _ : state) {
    const mostyle::Decomposition d = mostyle::decompose(x, options);
    iterations = d.iterations;
    benchmark::DoNotOptimize(d.components.data());
  }
  state.counters["iterations"] = iterations;
}
BENCHMARK(BM_Decompose)->Unit(benchmark::kMillisecond);

// Time per alternating round: a fixed number of rounds (no early stop), divided out.
void BM_DecomposeIteration(benchmark::State& state) {
  const int frames = static_cast<int>(state.range(0));
  const Eigen::MatrixXd x = synthetic_motion(frames, kJoints, 6, 0.02, 2);
  mostyle::DecompositionOptions options;
  options.max_iterations = 50;
  options.tolerance = 0.0;
  for (auto _ : state) {
    const mostyle::Decomposition d = mostyle::decompose(x, options);
    benchmark::DoNotOptimize(d.components.data());
  }
  // kIsIterationInvariantRate | kInvert gives CPU seconds / (value * runs): seconds per round.
  state.counters["per_iteration"] = benchmark::Counter(
      options.max_iterations,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_DecomposeIteration)->Arg(1000)->Arg(1800)->Unit(benchmark::kMillisecond);

void BM_DecomposeShared(benchmark::State& state) {
  const Eigen::MatrixXd a = synthetic_motion(kFrames, kJoints, 6, 0.02, 3);
  const Eigen::MatrixXd b = synthetic_motion(kFrames, kJoints, 6, 0.02, 4);
  for (auto _ : state) {
    const mostyle::StackedDecomposition d = mostyle::decompose_stacked({&a, &b});
    benchmark::DoNotOptimize(d.components.data());
  }
}
BENCHMARK(BM_DecomposeShared)->Unit(benchmark::kMillisecond);

void BM_SynthesizePaper(benchmark::State& state) {
  mostyle::DecompositionOptions options;
  options.max_iterations = 10;
  const mostyle::Decomposition a =
      mostyle::decompose(synthetic_motion(kFrames, kJoints, 6, 0.02, 7), options);
  const mostyle::Decomposition b =
      mostyle::decompose(synthetic_motion(kFrames, kJoints, 6, 0.02, 8), options);
  const mostyle::PaperSynthesis prepared = mostyle::prepare_paper_synthesis(
      a.weights, mostyle::core_components(a.components), mostyle::core_components(b.components));
  Eigen::MatrixXd out(kFrames, 3 * kJoints);
  for (auto _ : state) {
    mostyle::synthesize_paper(prepared, 0.5, out);
    benchmark::DoNotOptimize(out.data());
  }
}
BENCHMARK(BM_SynthesizePaper)->Unit(benchmark::kMicrosecond);

void BM_LimbLengths(benchmark::State& state) {
  const std::vector<int> parents = {-1, 0, 1, 2,  2, 4, 5, 6,  2, 8, 9, 10,
                                    0,  12, 13, 14, 0, 16, 17, 18};
  mostyle::test::Random random(9);
  const Eigen::MatrixXd reference = random.matrix(1, 3 * kJoints);
  const std::vector<double> lengths = mostyle::bone_lengths(reference, parents);
  const Eigen::MatrixXd input =
      reference.replicate(kFrames, 1) + 0.2 * random.matrix(kFrames, 3 * kJoints);
  // Re-applying to corrected positions does the same work as the first application.
  Eigen::MatrixXd positions = input;
  for (auto _ : state) {
    mostyle::apply_limb_lengths(positions, parents, lengths);
    benchmark::DoNotOptimize(positions.data());
  }
}
BENCHMARK(BM_LimbLengths)->Unit(benchmark::kMicrosecond);

}  // namespace
