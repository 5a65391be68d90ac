#pragma once
// Export: the blend's major-joint positions turned back into rotations
// of take A's full skeleton, in A's channel layout and rotation orders, so animators' tools read
// the blend as a BVH file.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "engine/export/channel_layout.h"
#include "engine/base/clip.h"

namespace mostyle {

// How closely the exported clip's major joints (by our FK) match the positions it was solved
// from: distances over all frames and joints, file units.
struct ExportFit {
  double max = 0.0;
  double mean = 0.0;
};

struct ExportResult {
  Clip clip;     // A's skeleton and channel layout at the output rate
  ExportFit fit;
};

// Solves, per frame, A's rotations from target positions of some of its joints.
//   clip:    take A as loaded (any rate; it is resampled to `fps` with resample_clip first, so
//            every joint has A's own local rotation at every output frame).
//   joints:  A's joint index of each target column (M distinct joints, no End Sites): the major
//            joints. Their hierarchy is A's: a column's parent is its nearest ancestor column.
//   world:   F x 3M target positions, A's units and world frame, at `fps`; F must equal the
//            resampled clip's frame count.
//   fps:     output frame rate; 0 or A's own rate keeps A's frames and frame time.
// Per frame, parents first:
//   - a column joint with one child column takes the smallest rotation that turns the direction
//     to that child (through any joints in between, at A's rotations) into the direction from
//     where the joint now is to the child's target, applied on top of A's local rotation (so
//     the bone's twist is A's); aiming from where the joint actually is keeps an error above
//     it from carrying down the chain;
//   - a column joint with several child columns (hips, chest) takes the best-fit rotation of
//     those directions (Kabsch), refined by least squares so the children themselves land. On
//     the way to a child, the first joint that turns on its own (a clavicle, a neck base, CMU's
//     LHipJoint or LowerBack: a "pivot") then aims at that child as a one-child joint would, so
//     the shoulders and the head reach their targets although A's rigid offsets do not line up
//     with the blend's directions. A pelvis without such joints (Bandai) is fitted rigidly;
//   - column joints without a child column (head, hands, toes) and all other joints (fingers,
//     further neck segments, End Sites) keep A's local rotations.
// The joint that carries the trajectory (the topmost column, or its nearest ancestor with
// position channels) gets position channels that put the topmost column on its target; other
// position channels keep A's values. Euler angles are in each joint's own order, unwrapped frame
// to frame (no jump over 180 degrees). A joint without exactly three rotation channels keeps
// A's values. Throws InputError on a bad joint index, a shape mismatch or a non-finite target.
// O(F x joints); allocates the output clip.
ExportResult solve_export(const Clip& clip, const std::vector<int>& joints, const Eigen::MatrixXd& world,
                          double fps);

// The solve of solve_export one frame at a time, for frames that arrive one by one (a live
// stream): the plan (which joint aims at which target, the joint that carries the trajectory)
// is made once for A's skeleton and its target joints, and each frame continues from the one
// solved before it (Euler angles unwrapped against its angles, a joint with several children
// started from its rotation), as solve_export's frames do. solve_export runs its frames through
// one of these.
class ExportFrameSolver {
 public:
  // skeleton: A's; joints: as solve_export takes them; source: A's name in messages. Throws
  // InputError on a bad joint index (End Sites included) or a joint listed twice. O(joints^2)
  // at most; allocates the plan.
  ExportFrameSolver(const Skeleton& skeleton, const std::vector<int>& joints, const std::string& source = "");
  ~ExportFrameSolver();
  ExportFrameSolver(ExportFrameSolver&&) noexcept;
  ExportFrameSolver& operator=(ExportFrameSolver&&) noexcept;

  // One frame. a_row: A's values at this frame (Skeleton::channel_count values, degrees and file
  // units); targets: 3M positions of the joints' targets (x, y, z per joint), A's units and
  // world frame, finite (not checked: solve_export checks); row: written whole, A's values with
  // the solved rotations and the carrier's position channels (may not be a_row). O(joints);
  // allocation-free.
  void solve(const double* a_row, const double* targets, double* row);
  // The next frame solved is a first frame again (nothing continues from the one before).
  void restart();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// The same with A's rotations taken at fractional frames `at` of A's clip (one per row of
// world; kinematics/resample.h sample_clip), frame time 1 / fps: a blend whose timing is not A's
// (trajectory/mixed_clock.h) takes A's rotations where the blend is in A's motion.
ExportResult solve_export_at(const Clip& clip, const std::vector<int>& joints, const Eigen::MatrixXd& world,
                             const Eigen::VectorXd& at, double fps);

// solve_export_at in `layout` (as export_blend_bvh below), without writing it: for callers that
// hand the clip over or write it later (write_motion_file writes the same file).
ExportResult solve_export_in_layout(const Clip& clip, const std::vector<int>& joints, const Eigen::MatrixXd& world,
                                    const Eigen::VectorXd& at, double fps, ChannelLayout layout);

// solve_export_at, then the clip written atomically to `path`: glTF 2.0 when it ends in .glb or
// .gltf, else BVH (io/motion_file.h write_motion_file). What the CLI's --out and the editor's
// export call. `layout`: kAsSource writes A's channel layout;
// kRotations writes with_rotation_channels of the solved clip (channel_layout.h), which readers
// that add position channels to the OFFSET (three.js) read as we do; the result's clip is then
// the one written (same joint positions, fit unchanged). The caller picks the default with
// default_channel_layout(clip). Throws InputError when the file cannot be written, or with
// kRotations when the solved clip has a changing position channel that layout cannot hold
// (nothing is written then).
ExportResult export_blend_bvh(const Clip& clip, const std::vector<int>& joints, const Eigen::MatrixXd& world,
                              const Eigen::VectorXd& at, double fps, const std::string& path,
                              ChannelLayout layout = ChannelLayout::kAsSource);

// max and mean distance between the clip's joints (FK at every frame) and `world`'s columns.
// Throws InputError on a shape mismatch. O(F x joints).
ExportFit export_fit(const Clip& clip, const std::vector<int>& joints, const Eigen::MatrixXd& world);

}  // namespace mostyle
