#pragma once
// The time warp between two takes as a smooth, monotone, fractional curve: samples
// along a common timeline, each giving a (fractional) frame of A and of B that match. Poses are
// sampled between frames along it, never skipped, so a warped take never jumps.
#include <Eigen/Core>
#include <utility>
#include <vector>

#include "engine/align/dtw.h"
#include "engine/kinematics/sample_rows.h"

namespace mostyle {

// U samples along the common timeline. a and b are non-decreasing; from one sample to the next
// the faster of the two advances by at most one frame (the curve's Chebyshev length is split
// evenly), so neither take is sampled more coarsely than its own frames.
struct TimeWarp {
  Eigen::VectorXd a;  // U: frames of A (fractional, A's working rate)
  Eigen::VectorXd b;  // U: frames of B
  int samples() const { return static_cast<int>(a.size()); }
};

// The warp through a path's vertices (slope_dtw.h SlopeDtwPath::steps, or any monotone path
// whose vertices strictly increase in i + j), smoothed by a moving average of smoothing_frames
// frames each side (ends kept in place), then resampled as TimeWarp says. Slopes stay within
// the path's. Throws InputError on an empty or non-monotone path or a negative smoothing.
// O(path length + U).
constexpr double kWarpSmoothingFrames = 3.0;  // at 30 fps: 0.1 s, under a footstep's duration
TimeWarp smooth_warp(const std::vector<std::pair<int, int>>& steps, double smoothing_frames = kWarpSmoothingFrames);

// Warps one after another, each starting where the one before ends (its first sample, the same
// frames as the last one before, is dropped). Throws InputError on none, an empty one or one
// that does not start where the one before ends.
TimeWarp joined_warps(const std::vector<TimeWarp>& warps);

// The paper's warp (`--dtw paper`): A's own frames 0..n-1 and, for each, the mean B
// frame the plain DTW path matches to it (dtw.h warp_map). B may skip frames from one sample to
// the next. Throws as warp_map does.
TimeWarp paper_warp(const DtwPath& path, int frames_a);

}  // namespace mostyle
