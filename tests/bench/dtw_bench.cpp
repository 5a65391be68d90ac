// Speed of engine/dtw.cpp. Targets (see the DTW task): 2000 x 2000 frames, d = 3, well under
// 20 ms for the path; 20000 x 18000 with its path in seconds and well under 1 GB.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "engine/align/dtw.h"
#include "engine/align/slope_dtw.h"
#include "engine/align/time_warp.h"

namespace {

// A left-foot-like signal: periodic steps (x forward swing, y lift, z sway) with a little
// noise, `speed` steps per second at 30 fps.
Eigen::MatrixXd foot_signal(int frames, double speed, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.01);
  const double kTwoPi = 6.283185307179586;
  Eigen::MatrixXd x(frames, 3);
  for (int i = 0; i < frames; ++i) {
    const double phase = kTwoPi * speed * i / 30.0;
    x(i, 0) = std::sin(phase) + noise(rng);
    x(i, 1) = std::max(0.0, std::sin(phase + 1.0)) * 0.2 + noise(rng);
    x(i, 2) = 0.1 * std::cos(0.5 * phase) + noise(rng);
  }
  return x;
}

void set_cells(benchmark::State& state, double cells) {
  state.counters["cells/s"] =
      benchmark::Counter(cells, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_AlignDtw(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), m = static_cast<int>(state.range(1));
  const Eigen::MatrixXd a = foot_signal(n, 1.0, 1), b = foot_signal(m, 1.1, 2);
  mostyle::DtwOptions o;
  o.band = static_cast<int>(state.range(2));
  for (auto _ : state) benchmark::DoNotOptimize(mostyle::align_dtw(a, b, o));
  // Cells in the band: |j - i(m-1)/(n-1)| <= band, counted row by row.
  double cells = double(n) * m;
  if (o.band >= 0 && n > 1) {
    cells = 0.0;
    for (int i = 0; i < n; ++i) {
      const double centre = double(i) * (m - 1) / (n - 1);
      cells += std::min<double>(m - 1, std::floor(centre + o.band)) -
               std::max(0.0, std::ceil(centre - o.band)) + 1.0;
    }
  }
  set_cells(state, cells);
}

void BM_AlignDtwDivideAndConquer(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), m = static_cast<int>(state.range(1));
  const Eigen::MatrixXd a = foot_signal(n, 1.0, 1), b = foot_signal(m, 1.1, 2);
  mostyle::DtwOptions o;
  o.pointer_budget_bytes = 0;  // no back-pointers at all: the linear-memory worst case
  for (auto _ : state) benchmark::DoNotOptimize(mostyle::align_dtw(a, b, o));
  set_cells(state, double(n) * m);
}

// The default alignment (slope-limited, open ends, automatic end penalty: two passes).
// Arg 2: the back-pointer budget in MB (0: checkpoints every few rows, the bounded-memory path).
void BM_AlignSlopeDtw(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), m = static_cast<int>(state.range(1));
  const Eigen::MatrixXd a = foot_signal(n, 1.0, 1), b = foot_signal(m, 1.1, 2);
  mostyle::SlopeDtwOptions o;
  if (state.range(2) >= 0) o.pointer_budget_bytes = static_cast<std::size_t>(state.range(2)) << 20;
  for (auto _ : state) benchmark::DoNotOptimize(mostyle::align_slope_dtw(a, b, o));
  set_cells(state, double(n) * m);  // the full-resolution pass (the first runs on about 250 000 cells)
}

// The path turned into the smooth fractional warp.
void BM_SmoothWarp(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Eigen::MatrixXd a = foot_signal(n, 1.0, 1), b = foot_signal(n, 1.1, 2);
  const mostyle::SlopeDtwPath path = mostyle::align_slope_dtw(a, b);
  for (auto _ : state) benchmark::DoNotOptimize(mostyle::smooth_warp(path.steps));
  state.counters["samples"] = mostyle::smooth_warp(path.steps).samples();
}

}  // namespace

BENCHMARK(BM_AlignSlopeDtw)->Args({1800, 1800, -1})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AlignSlopeDtw)->Args({1800, 1800, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AlignSlopeDtw)->Args({20000, 18000, -1})->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AlignSlopeDtw)->Args({20000, 18000, 16})->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SmoothWarp)->Arg(1800)->Unit(benchmark::kMicrosecond);

BENCHMARK(BM_AlignDtw)->Args({2000, 2000, -1})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AlignDtw)->Args({2000, 2000, 100})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AlignDtwDivideAndConquer)->Args({2000, 2000})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AlignDtw)
    ->Name("BM_AlignDtwLong")
    ->Args({20000, 18000, -1})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
BENCHMARK(BM_AlignDtwDivideAndConquer)
    ->Name("BM_AlignDtwLongDivideAndConquer")
    ->Args({20000, 18000})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
