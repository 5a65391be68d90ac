#pragma once
// The frames an export writes: a synthesized motion resampled to the output frame rate over a
// range of its time, each with the frame of take A it shows, ready for export_solve.h
// export_blend_bvh, at the frame rate and over the range the person asks for.
#include <Eigen/Core>

namespace mostyle {

// Output rates above this are refused (a typing slip, not a capture rate).
constexpr double kMaxExportFps = 1000.0;
// Rounding allowed where a range end meets a frame, as a fraction of a frame: of an output
// frame for the last frame inside the range, of a working frame for the range's bounds.
constexpr double kExportTimeTolerance = 1e-6;

struct ExportFrames {
  Eigen::MatrixXd world;  // K x 3M: positions at the output rate, the motion's units
  Eigen::VectorXd at;     // K: A's clip frame (fractional, A's own rate) each output frame shows
  double fps = 0.0;       // the output rate, frames per second
  int frames() const { return static_cast<int>(world.rows()); }
};

// Seconds from the first to the last of `frames` frames at `fps`: (frames - 1) / fps, 0 for
// fewer than two frames or an fps that is not positive.
double motion_length_s(Eigen::Index frames, double fps);

// Frames at `fps` from first_s to last_s inclusive (seconds, first_s <= last_s):
// floor((last_s - first_s) * fps + kExportTimeTolerance) + 1. No checks; O(1).
int export_frame_count(double first_s, double last_s, double fps);

// The motion resampled for export.
//   world:       F x 3M positions at working_fps (a MixResult's motion.world, mix_palette.h), F >= 1
//   at:          F source frames in A's clip (mix_palette.h source_frames_in_clip)
//   working_fps: the rate of world's rows; row i is at i / working_fps seconds
//   out_fps:     the output rate, in (0, kMaxExportFps]
//   first_s, last_s: the range, seconds of the motion: 0 <= first_s <= last_s <= its length
//                (motion_length_s(F, working_fps)); a bound off by less than
//                kExportTimeTolerance of a working frame is taken as the end it misses
// Output frame k is at first_s + k / out_fps, for k in [0, export_frame_count(first_s, last_s,
// out_fps)): rows of world and at linearly interpolated there (kinematics/sample_rows.h);
// a frame that lands on a working frame (within 1e-9 of one) copies it. Throws InputError with
// one sentence on a rate that is not a finite number in (0, kMaxExportFps] (either rate), a
// range that is not finite, empty (first_s after last_s) or outside the motion, no frames, or
// at.size() != F. O(K x 3M); allocates the result.
ExportFrames export_frames(const Eigen::MatrixXd& world, const Eigen::VectorXd& at, double working_fps,
                           double out_fps, double first_s, double last_s);

// A seamless loop (post/loop.h, a MixResult's motion.loop with cycles > 0) resampled for export: world's
// F rows are one period, frame F would repeat frame 0 moved by `travel` (the root's (x, z)
// travel per loop, LoopCut::travel, added to every joint's x and z). K = round(F * out_fps /
// working_fps) frames (at least 1) evenly over the period, frame k at row k * F / K, between
// row F - 1 and that repeat of row 0 at the seam; A's frame there is extrapolated from the last
// two. So the file repeats without a hitch at any rate; it plays for K / out_fps seconds, within
// half an output frame of the loop's F / working_fps. With out_fps == working_fps it is world
// and at as they are. world's columns must be a multiple of 3. Throws InputError as
// export_frames does on a bad rate, no frames or a size mismatch. O(K x 3M).
ExportFrames export_loop_frames(const Eigen::MatrixXd& world, const Eigen::VectorXd& at, double working_fps,
                                double out_fps, const Eigen::Vector2d& travel);

}  // namespace mostyle
