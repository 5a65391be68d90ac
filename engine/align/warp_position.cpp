#include "engine/align/warp_position.h"

#include <algorithm>

namespace mostyle {

double warp_position(const TimeWarp& warp, const CommonTimeline& timeline, int take, double sample) {
  const Eigen::Index n = timeline.samples(), u = warp.samples();
  if (n == 0 || u == 0 || take < 1 || take >= timeline.takes()) return 0.0;
  const double s = std::clamp(sample, 0.0, double(n - 1));
  const Eigen::Index i = std::min<Eigen::Index>(static_cast<Eigen::Index>(s), std::max<Eigen::Index>(n - 2, 0));
  const double f = n > 1 ? s - double(i) : 0.0;
  auto at = [&](const Eigen::VectorXd& v) { return n > 1 ? v[i] + f * (v[i + 1] - v[i]) : v[0]; };
  const double along = at(timeline.frames[0]) + at(timeline.frames[static_cast<size_t>(take)]);
  auto sum = [&](Eigen::Index k) { return warp.a[k] + warp.b[k]; };
  if (along <= sum(0)) return 0.0;
  if (along >= sum(u - 1)) return double(u - 1);
  Eigen::Index lo = 0, hi = u - 1;  // sum(lo) < along <= sum(hi)
  while (hi - lo > 1) {
    const Eigen::Index mid = (lo + hi) / 2;
    (sum(mid) < along ? lo : hi) = mid;
  }
  const double d = sum(hi) - sum(lo);
  return d > 0.0 ? double(lo) + (along - sum(lo)) / d : double(hi);
}

}  // namespace mostyle
