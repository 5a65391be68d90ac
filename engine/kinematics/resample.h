#pragma once
// Changing a clip's frame rate.
#include <Eigen/Core>
#include <vector>

#include "engine/base/clip.h"

namespace mostyle {

// The clip resampled to `fps` frames per second over the same duration: rotations of joints
// with three rotation channels by quaternion slerp (Euler angles unwrapped frame to frame),
// other channels linearly. The source rate is the snapped one (0.008333 s counts as 120 Hz).
// Frames: floor(duration * fps) + 1; an output frame that lands on a source frame copies it
// (its rotation angles changed only to an equivalent set, to stay continuous). Throws InputError when fps or the clip's frame
// time is not a positive number or the result would hold over 1e8 values.
// O(output frames * channels). joints, when not empty: only the channels of these joints and
// their ancestors are sampled (all their positions need), every other channel is 0.
Clip resample_clip(const Clip& clip, double fps, const std::vector<int>& joints = {});

// The clip sampled at fractional frames `at` of its own (clamped to its range), interpolated as
// resample_clip does, with frame time 1 / fps: what a time warp needs (take A's rotations at a
// blend's output frames). Throws InputError on no frames, a bad fps, a non-finite frame or too
// many values. O(at.size() * channels). joints: as for resample_clip.
Clip sample_clip(const Clip& clip, const Eigen::VectorXd& at, double fps, const std::vector<int>& joints = {});

}  // namespace mostyle
