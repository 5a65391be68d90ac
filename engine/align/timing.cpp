#include "engine/align/timing.h"

#include <algorithm>
#include <cmath>

#include "engine/io/error.h"

namespace mostyle {

Eigen::VectorXd blended_clock(const TimeWarp& warp, double w) {
  if (!std::isfinite(w)) throw InputError("expected a finite timing weight");
  if (warp.samples() == 0) throw InputError("cannot time a blend along an empty warp");
  Eigen::VectorXd clock(warp.samples());
  clock[0] = 0.0;
  for (int k = 1; k < warp.samples(); ++k) {
    const double step = (1.0 - w) * (warp.a[k] - warp.a[k - 1]) + w * (warp.b[k] - warp.b[k - 1]);
    clock[k] = clock[k - 1] + std::max(0.0, step);
  }
  return clock;
}

void blended_timeline(const TimeWarp& warp, double w, Eigen::VectorXd& u) {
  if (!std::isfinite(w)) throw InputError("expected a finite timing weight");
  const int samples = warp.samples();
  if (samples == 0) throw InputError("cannot time a blend along an empty warp");
  // One pass: the clock is accumulated as the walk goes, so nothing is allocated but u.
  double total = 0.0;
  for (int k = 1; k < samples; ++k)
    total += std::max(0.0, (1.0 - w) * (warp.a[k] - warp.a[k - 1]) + w * (warp.b[k] - warp.b[k - 1]));
  const int frames = static_cast<int>(std::floor(total + 1e-9)) + 1;
  u.resize(frames);
  int k = 0;
  double before = 0.0, after = 0.0;  // clock at samples k and k + 1
  if (samples > 1) after = std::max(0.0, (1.0 - w) * (warp.a[1] - warp.a[0]) + w * (warp.b[1] - warp.b[0]));
  for (int f = 0; f < frames; ++f) {
    while (k + 1 < samples - 1 && after < f) {
      ++k;
      before = after;
      after += std::max(0.0, (1.0 - w) * (warp.a[k + 1] - warp.a[k]) + w * (warp.b[k + 1] - warp.b[k]));
    }
    if (samples == 1) {
      u[f] = 0.0;
      continue;
    }
    const double span = after - before;
    u[f] = k + (span > 0 ? std::clamp((f - before) / span, 0.0, 1.0) : 0.0);
  }
}

}  // namespace mostyle
