#include "engine/align/time_warp.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/base/error.h"

namespace mostyle {

TimeWarp smooth_warp(const std::vector<std::pair<int, int>>& steps, double smoothing_frames) {
  if (steps.empty()) throw InputError("cannot build a time warp from an empty DTW path");
  if (!(smoothing_frames >= 0) || !std::isfinite(smoothing_frames))
    throw InputError("expected a warp smoothing of 0 or more frames");
  for (size_t k = 1; k < steps.size(); ++k)
    if (steps[k].first < steps[k - 1].first || steps[k].second < steps[k - 1].second ||
        steps[k].first + steps[k].second <= steps[k - 1].first + steps[k - 1].second)
      throw InputError("DTW path is not monotone at vertex " + std::to_string(k));
  // Dense polyline at every integer s = i + j (the vertices are on it).
  const int s0 = steps.front().first + steps.front().second;
  const int count = steps.back().first + steps.back().second - s0 + 1;
  Eigen::VectorXd pa(count), pb(count);
  pa[0] = steps.front().first;
  pb[0] = steps.front().second;
  for (size_t k = 0; k + 1 < steps.size(); ++k) {
    const auto [i0, j0] = steps[k];
    const auto [i1, j1] = steps[k + 1];
    const int span = (i1 + j1) - (i0 + j0);
    for (int t = 1; t <= span; ++t) {
      const int s = i0 + j0 + t - s0;
      pa[s] = i0 + (i1 - i0) * double(t) / span;
      pb[s] = j0 + (j1 - j0) * double(t) / span;
    }
  }
  // Moving average over 2 h + 1 points, the window shrinking symmetrically at the ends so they
  // stay put; a window that slides or grows towards later points only adds larger values, so
  // the averages stay monotone. s advances about 2 per frame of each take.
  const int h = static_cast<int>(std::lround(2.0 * smoothing_frames));
  Eigen::VectorXd ca(count + 1), cb(count + 1);  // prefix sums
  ca[0] = cb[0] = 0.0;
  for (int t = 0; t < count; ++t) {
    ca[t + 1] = ca[t] + pa[t];
    cb[t + 1] = cb[t] + pb[t];
  }
  Eigen::VectorXd sa(count), sb(count);
  for (int t = 0; t < count; ++t) {
    const int w = std::min({h, t, count - 1 - t});
    sa[t] = (ca[t + w + 1] - ca[t - w]) / (2 * w + 1);
    sb[t] = (cb[t + w + 1] - cb[t - w]) / (2 * w + 1);
  }
  // Resample evenly in Chebyshev length: one sample per frame of whichever take moves faster.
  Eigen::VectorXd length(count);
  length[0] = 0.0;
  for (int t = 1; t < count; ++t)
    length[t] = length[t - 1] + std::max(sa[t] - sa[t - 1], sb[t] - sb[t - 1]);
  const double total = length[count - 1];
  const int samples = std::max(1, static_cast<int>(std::ceil(total - 1e-9)) + 1);
  TimeWarp warp;
  warp.a.resize(samples);
  warp.b.resize(samples);
  int t = 0;
  for (int u = 0; u < samples; ++u) {
    const double at = samples == 1 ? 0.0 : total * u / (samples - 1);
    while (t + 1 < count - 1 && length[t + 1] <= at) ++t;
    if (count == 1) {
      warp.a[u] = sa[0];
      warp.b[u] = sb[0];
      continue;
    }
    const double span = length[t + 1] - length[t];
    const double f = span > 0 ? std::clamp((at - length[t]) / span, 0.0, 1.0) : 0.0;
    warp.a[u] = sa[t] + f * (sa[t + 1] - sa[t]);
    warp.b[u] = sb[t] + f * (sb[t + 1] - sb[t]);
  }
  warp.a[samples - 1] = sa[count - 1];
  warp.b[samples - 1] = sb[count - 1];
  return warp;
}

TimeWarp joined_warps(const std::vector<TimeWarp>& warps) {
  if (warps.empty()) throw InputError("cannot join no time warps");
  Eigen::Index samples = 0;
  for (size_t k = 0; k < warps.size(); ++k) {
    const TimeWarp& w = warps[k];
    if (w.samples() == 0) throw InputError("cannot join an empty time warp");
    if (k > 0 && (w.a[0] != warps[k - 1].a[warps[k - 1].samples() - 1] ||
                  w.b[0] != warps[k - 1].b[warps[k - 1].samples() - 1]))
      throw InputError("cannot join time warps that do not meet: warp " + std::to_string(k) +
                       " starts where warp " + std::to_string(k - 1) + " does not end");
    samples += w.samples() - (k > 0 ? 1 : 0);
  }
  TimeWarp out;
  out.a.resize(samples);
  out.b.resize(samples);
  Eigen::Index at = 0;
  for (size_t k = 0; k < warps.size(); ++k) {
    const Eigen::Index skip = k > 0 ? 1 : 0, n = warps[k].samples() - skip;
    out.a.segment(at, n) = warps[k].a.tail(n);
    out.b.segment(at, n) = warps[k].b.tail(n);
    at += n;
  }
  return out;
}

TimeWarp paper_warp(const DtwPath& path, int frames_a) {
  TimeWarp warp;
  warp.b = warp_map(path, frames_a);
  warp.a = Eigen::VectorXd::LinSpaced(frames_a, 0.0, frames_a - 1.0);
  return warp;
}

}  // namespace mostyle
