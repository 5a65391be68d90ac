#pragma once
// The time warp between two takes as a smooth, monotone, fractional curve: samples
// along a common timeline, each giving a (fractional) frame of A and of B that match. Poses are
// sampled between frames along it, never skipped, so a warped take never jumps.
#include <Eigen/Core>
#include <utility>
#include <vector>

#include "engine/align/dtw.h"

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

// The paper's warp (`--dtw paper`): A's own frames 0..n-1 and, for each, the mean B
// frame the plain DTW path matches to it (dtw.h warp_map). B may skip frames from one sample to
// the next. Throws as warp_map does.
TimeWarp paper_warp(const DtwPath& path, int frames_a);

// Rows of x (frames x channels) at fractional rows t (each clamped to [0, rows - 1]), linearly
// interpolated, into out (t.size() x channels; no allocation when it has that size). Throws
// InputError when x has no rows. O(t.size() x channels).
void sample_rows(const Eigen::MatrixXd& x, const Eigen::VectorXd& t, Eigen::MatrixXd& out);
Eigen::MatrixXd sample_rows(const Eigen::MatrixXd& x, const Eigen::VectorXd& t);

// The same with the rows and fractions worked out once for several matrices of `rows` rows:
// the alpha slider's path samples a few of them at every output frame.
struct RowSampler {
  Eigen::VectorXi row;    // K: the row before each sample time
  Eigen::VectorXd frac;   // K: how far towards the next row, 0..1
  void set(const Eigen::VectorXd& t, Eigen::Index rows);  // rows >= 1; no allocation once sized
  // out = x at the times (resized to K x x.cols()).
  void apply(const Eigen::MatrixXd& x, Eigen::MatrixXd& out) const;
  // out += weight times x at the times (out already K x x.cols()).
  void accumulate(const Eigen::MatrixXd& x, double weight, Eigen::MatrixXd& out) const;
};

}  // namespace mostyle
