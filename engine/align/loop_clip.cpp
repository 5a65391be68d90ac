#include "engine/align/loop_clip.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mostyle {
namespace {

// A loop's steps next to its seam are at least this share of its median step: one that comes to
// rest at both ends is a take from standing to standing, not a loop.
constexpr double kSeamMotion = 0.1;
// A return to the first pose: the distance from it falls below this share of its largest ...
constexpr double kReturnEnter = 0.25;
// ... and the return ends when it rises above this share again (hysteresis: noise around one
// threshold is not several returns).
constexpr double kReturnLeave = 0.5;

// RMS over joints of the distance between two poses (rows of 3M values).
template <typename A, typename B>
double pose_distance(const A& a, const B& b) {
  const Eigen::Index joints = a.size() / 3;
  return joints > 0 ? std::sqrt((a - b).squaredNorm() / double(joints)) : 0.0;
}

// Times the poses come back near the first one between the clip's ends (not counting the ends).
int returns_to_first(const Eigen::MatrixXd& local) {
  const Eigen::Index frames = local.rows();
  std::vector<double> d(static_cast<size_t>(frames));
  double largest = 0.0;
  for (Eigen::Index t = 0; t < frames; ++t) {
    d[static_cast<size_t>(t)] = pose_distance(local.row(t), local.row(0));
    largest = std::max(largest, d[static_cast<size_t>(t)]);
  }
  // Leave the start's neighbourhood first; a return that lasts to the end is the end's.
  Eigen::Index t = 0;
  while (t < frames && d[static_cast<size_t>(t)] <= kReturnLeave * largest) ++t;
  int returns = 0;
  bool near = false;
  for (; t < frames; ++t) {
    const double v = d[static_cast<size_t>(t)];
    if (!near && v < kReturnEnter * largest) {
      near = true;
      ++returns;
    } else if (near && v > kReturnLeave * largest) {
      near = false;
    }
  }
  return near ? returns - 1 : returns;
}

}  // namespace

int loop_clip_frames(const Eigen::MatrixXd& local, int max_frames, int max_returns) {
  const Eigen::Index frames = local.rows();
  if (frames < 4 || local.cols() < 3 || frames - 1 > max_frames) return 0;  // too short, or too long for a loop
  const double joints = double(local.cols() / 3);
  const Eigen::VectorXd step_sizes =
      ((local.bottomRows(frames - 1) - local.topRows(frames - 1)).rowwise().squaredNorm() / joints).cwiseSqrt();
  const std::vector<double> steps(step_sizes.data(), step_sizes.data() + step_sizes.size());
  std::vector<double> sorted = steps;
  const auto mid = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
  std::nth_element(sorted.begin(), mid, sorted.end());
  const double step = *mid;
  if (!(step > 0.0) || !std::isfinite(step)) return 0;  // still: nothing to loop

  const Eigen::RowVectorXd first = local.row(0), last = local.row(frames - 1);
  const Eigen::RowVectorXd step_on = 0.5 * ((local.row(1) - first) + (last - local.row(frames - 2)));
  const double repeat_seam = pose_distance(last, first);
  const double follow_seam = pose_distance(Eigen::RowVectorXd(last + step_on), first);
  const int loop = static_cast<int>(repeat_seam <= follow_seam ? frames - 1 : frames);
  if (std::min(repeat_seam, follow_seam) > step || loop > max_frames) return 0;
  // A take that comes to rest at both ends (from standing to standing) stops at its seam; a loop
  // moves on through it.
  if (std::min(steps.front(), steps.back()) < kSeamMotion * step) return 0;
  if (returns_to_first(local) > max_returns) return 0;
  return loop;
}

}  // namespace mostyle
