#include "engine/align/timing.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/io/error.h"

namespace mostyle {

namespace {
// The blended clock's advance from sample k - 1 to k: never slower than the slower take with a
// weight (only extrapolation, w outside [0, 1], reaches that bound), as mixed_timeline's.
double blend_step(const TimeWarp& warp, double w, int k) {
  const double da = warp.a[k] - warp.a[k - 1], db = warp.b[k] - warp.b[k - 1];
  const double slowest = w == 0.0 ? da : w == 1.0 ? db : std::min(da, db);
  return std::max((1.0 - w) * da + w * db, slowest);
}
}  // namespace

Eigen::VectorXd blended_clock(const TimeWarp& warp, double w) {
  if (!std::isfinite(w)) throw InputError("expected a finite timing weight");
  if (warp.samples() == 0) throw InputError("cannot time a blend along an empty warp");
  Eigen::VectorXd clock(warp.samples());
  clock[0] = 0.0;
  for (int k = 1; k < warp.samples(); ++k) {
    clock[k] = clock[k - 1] + std::max(0.0, blend_step(warp, w, k));
  }
  return clock;
}

namespace {

// Output frame f at the sample position where the clock reaches f; step(k) is the clock's
// advance from sample k - 1 to k (negative advances hold). One pass to count the frames, one to
// place them: nothing is allocated but u.
template <typename Step>
void timeline_from_steps(int samples, const Step& step, Eigen::VectorXd& u) {
  double total = 0.0;
  for (int k = 1; k < samples; ++k) total += std::max(0.0, step(k));
  const int frames = static_cast<int>(std::floor(total + 1e-9)) + 1;
  u.resize(frames);
  int k = 0;
  double before = 0.0, after = 0.0;  // clock at samples k and k + 1
  if (samples > 1) after = std::max(0.0, step(1));
  for (int f = 0; f < frames; ++f) {
    while (k + 1 < samples - 1 && after < f) {
      ++k;
      before = after;
      after += std::max(0.0, step(k + 1));
    }
    if (samples == 1) {
      u[f] = 0.0;
      continue;
    }
    const double span = after - before;
    u[f] = k + (span > 0 ? std::clamp((f - before) / span, 0.0, 1.0) : 0.0);
  }
}

}  // namespace

void blended_timeline(const TimeWarp& warp, double w, Eigen::VectorXd& u) {
  if (!std::isfinite(w)) throw InputError("expected a finite timing weight");
  const int samples = warp.samples();
  if (samples == 0) throw InputError("cannot time a blend along an empty warp");
  timeline_from_steps(samples, [&](int k) { return blend_step(warp, w, k); }, u);
}

void mixed_timeline(const CommonTimeline& timeline, const std::vector<double>& weights, int first, int last,
                    Eigen::VectorXd& u) {
  if (static_cast<int>(weights.size()) != timeline.takes())
    throw InputError("expected " + std::to_string(timeline.takes()) + " timing weights, found " +
                     std::to_string(weights.size()));
  for (double w : weights)
    if (!std::isfinite(w)) throw InputError("expected finite timing weights");
  if (first < 0 || last < first || last >= timeline.samples())
    throw InputError("cannot time a mix over samples " + std::to_string(first) + " to " + std::to_string(last) +
                     " of a timeline of " + std::to_string(timeline.samples()));
  // Never slower than the slowest take with a weight: a negative weight (a transfer's -s on the
  // neutral take) could stall the clock, and the output would then run through the takes' frames
  // faster than any of them moves. Weights within [0, 1] never reach the bound.
  timeline_from_steps(
      last - first + 1,
      [&](int k) {
        double step = 0.0, slowest = INFINITY;
        for (size_t i = 0; i < weights.size(); ++i) {
          const double advance = timeline.frames[i][first + k] - timeline.frames[i][first + k - 1];
          step += weights[i] * advance;
          if (weights[i] != 0.0) slowest = std::min(slowest, advance);
        }
        return std::max(step, slowest);
      },
      u);
  u.array() += first;
}

}  // namespace mostyle
