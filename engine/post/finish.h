#pragma once
// The last steps every synthesized motion takes, a pair's blend or a palette's mix: the root
// and the foot contacts read at the output frames, the loop cut when asked, the poses placed
// in the world, the limb-length constraint (paper 3.7) and the foot lock.
#include <Eigen/Core>
#include <vector>

#include "engine/kinematics/sample_rows.h"
#include "engine/measure/foot_contact.h"
#include "engine/post/foot_lock.h"
#include "engine/post/loop.h"
#include "engine/post/speed_limit.h"
#include "engine/post/swing_clearance.h"

namespace mostyle {

struct FinishOptions {
  bool limb_lengths = true;  // paper 3.7
  bool foot_lock = true;     // pin planted feet after the limb lengths (foot_lock.h)
  bool loop = false;         // cut a seamless loop of whole gait cycles (loop.h)
  // The motion is one whole loop whose last frame shows its first pose again (a loop clip's cycle
  // as the reference, its clock landed on the loop's end: mixed_clock.h land_on_last): that frame is
  // cut off and the seam closed, so the last frame leads into the first as any frame into the
  // next. Replaces `loop`.
  bool closed = false;
};

// What the motion is measured and rigged with.
struct FinishRig {
  const std::vector<int>* parents = nullptr;    // within the motion's columns
  const std::vector<double>* lengths = nullptr;  // the reference's bone lengths per column
  const FootRig* feet = nullptr;
  double short_bone_fraction = 0.5;             // limb_length.h LimbLengthOptions::short_fraction
  FootLockLimits lock_limits;  // what the foot lock keeps the motion under (the takes' fastest joint and planted feet)
};

struct FinishedMotion {
  Eigen::MatrixXd world;            // K x 3M
  Eigen::MatrixXd contacts;         // K x 2
  LoopCut loop;                     // with FinishOptions::loop: where it was cut
  double limb_length_max_error = 0; // after the constraint (before it when off)
  // How fast its planted feet move (planted_feet.h), file units per second: before the foot
  // lock and after it (never more: the lock moves planted feet no faster than they were).
  double foot_sliding_raw = 0;
  double foot_sliding_cleaned = 0;
  // How fast its fastest joint moves after the clean-up (fastest_joint.h), file units per second:
  // what pops are told by, against the takes' (FootLockLimits::fastest_joint).
  double fastest_joint = 0;
};

// A foot joint the mixed takes move faster than this (body heights per second, their planted
// drift into or out of a frame) is not held there, however low: a foot that skims the floor at a
// swing's speed (a kick's dragging foot) is not standing on it, and neither pinned nor set down.
constexpr double kHeldFootSpeed = 0.25;

struct FinishScratch {
  Eigen::MatrixXd before_lock;  // a loop's world before the foot lock
  Eigen::MatrixXd ground, drift, planted;
  std::vector<double> heights;
  std::vector<double> steps;  // the fastest joint's speed per frame step (fastest_joint_speed)
  Eigen::VectorXd heading;
  Eigen::VectorXd heading_uncut;  // the headings before a loop's cut, for the body drift
  Eigen::MatrixXd feet_height;    // feet_height cut to a loop's frames
  Eigen::MatrixXd air, held;      // where it is above kSwingAirBands, and within one band
  Eigen::VectorXd seam_share;     // a loop's seam taken up over a leg's swings
  FootLockScratch foot;
  SwingClearanceScratch swing;
  SpeedLimitScratch speed;
};

// Where finish_preview places the poses: the output's root path and contacts on the samples (U
// of them), and the sampler that reads them at the output frames (the mixed trajectory's).
struct FinishPath {
  const RowSampler* sampler = nullptr;          // set on the K output frames' sample positions
  const Eigen::MatrixXd* ground_u = nullptr;    // U x 2: the root's ground point (x, z)
  const Eigen::VectorXd* heading_u = nullptr;   // U: its heading, radians
  const Eigen::MatrixXd* contacts_u = nullptr;  // U x 2: the foot contacts, 1 planted
};

// The clean-up in two calls, so that a preview can show a motion before its slow passes are done.
// finish_preview places the poses in the world: local (K x 3M canonical poses at the output
// frames) and u (their K sample positions, path.sampler set on them) along the path, the contacts
// read at the output frames, the loop cut when asked (local and u cut to the loop's frames;
// closed: all but the last), the limb-length constraint; out.world, out.contacts and out.loop
// set, the measures 0. Throws InputError when a loop is asked of a motion without two foot
// strikes. O(K x M).
void finish_preview(const FinishPath& path, const FinishRig& rig, const FinishOptions& options, Eigen::MatrixXd& local,
                    Eigen::VectorXd& u, FinishScratch& scratch, FinishedMotion& out);

// finish_rest, given the same rig, options and scratch and the out finish_preview left, runs the
// rest: the speed limit, the foot lock, the measures. body_drift: when given (K x 2 kFootJoints:
// x, z per foot joint, planted_feet.h), how far each planted foot joint may move from output
// frame k to k + 1 in the body's frame there (the mixed takes' own planted moves, mix_palette.cpp
// planted_drift), for the foot lock (apply_foot_lock's drift). feet_height: when given (K x
// kFootJoints, before any loop cut), how high the mixed takes hold each foot joint at output frame
// k, in planted bands above its floor (mix_palette.cpp feet_heights): with the foot lock, joints
// above kSwingAirBands are first lifted clear of the floor (swing_clearance.h; not in a loop,
// whose seam is closed by blending its ends), and joints within one band that the takes move no
// faster than kHeldFootSpeed (by body_drift) are pinned as the output's planted ones are
// (apply_foot_lock's held) and set to the takes' heights (settle_held_feet). foot_sliding_raw and _cleaned:
// planted_feet.h's measure before and after the lift and the lock. O(K x M) with a larger
// constant (the lock may try up to seven times); allocation-free once sized, except the loop.
void finish_rest(const FinishRig& rig, const FinishOptions& options, FinishScratch& scratch, FinishedMotion& out,
                 const Eigen::MatrixXd* body_drift = nullptr, const Eigen::MatrixXd* feet_height = nullptr);

}  // namespace mostyle
