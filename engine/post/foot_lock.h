#pragma once
// The foot lock (beyond the paper): the planted feet of a mix pinned in place with two-bone IK
// (hip-knee-ankle, kinematics/two_bone_ik.h) so it does not skate, where the measures of
// measure/foot_contact.h and measure/planted_feet.h find them planted. Works on major-joint
// positions (frames x 3M, file units, Y up), the same matrices the pipeline blends.
#include <Eigen/Core>
#include <array>
#include <utility>
#include <vector>

#include "engine/measure/foot_contact.h"

namespace mostyle {

// Buffers apply_foot_lock reuses, so the lock does not allocate once they have the right size.
struct FootLockScratch {
  Eigen::VectorXd weight;  // F: 1 where the ankle is moved, 0 where it is left as it is
  Eigen::MatrixXd target;  // F x 2: the horizontal offset (x, z) that moves it
  Eigen::MatrixXd planted; // F x 4: planted_feet.h's planted frames
  Eigen::VectorXi pinned;  // F: 1 on the frames a foot is pinned over
  Eigen::VectorXd ease;    // F: after a stance, how far its offset has eased to the next (-1 elsewhere)
  Eigen::VectorXd swing;   // F: within a swing, how far the offset has gone from one stance's to the next's
  Eigen::VectorXd yaw;     // F: the turn (radians about the vertical) that holds a planted foot's heading
  Eigen::MatrixXd before;  // F x 9: a leg's knee, ankle and toe as they were
  std::vector<double> heights;
  std::vector<std::pair<Eigen::Index, Eigen::Index>> stances;  // a leg's stances, first and last frame
  // F x 18: the legs' knees, ankles and toes as they were, and in the best try, where the lock
  // tries again.
  Eigen::MatrixXd original, best;
  // F x 18: the legs before the lock, and as locked where the lock tries again from a lowered body.
  Eigen::MatrixXd unlocked, locked;
  // F x 15, a frame a row: both hips and one leg's knee, ankle and toe, as the lock moves the leg.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> leg_rows;
  std::array<double, 2> before_moves{};  // per leg: its planted joints' moves before the lock
  const Eigen::MatrixXd* held = nullptr;  // apply_foot_lock's, for its tries
  // F: how far the body comes down so that the pinned feet are within the legs' reach, and the
  // running maximum it is smoothed from.
  Eigen::VectorXd drop, drop_max;
  bool record_drop = false;  // a try records into drop what each frame's targets need
};

// What the lock keeps an output under, from the takes it mixes (0: no limit), units per second.
struct FootLockLimits {
  // No step of a swing or fade is made faster than this by the change of offset it carries (each
  // foot joint's own speed plus that change): the stances on either side are pinned in part instead
  // (the mixed takes' fastest joint, fastest_joint.h: no pops).
  double fastest_joint = 0.0;
  // With a drift: where allowing all of it leaves the planted feet (planted_feet.h's measure)
  // faster than this, less of it is allowed, down to none (the takes' own planted feet, weighted).
  double planted_speed = 0.0;
};

// Locks planted feet in place, in world (F x 3M) itself. A foot is pinned over its stances, the
// stretches of frames where one of its joints is planted by planted_feet.h's measure (within a
// band of its floor: a heel coming down, a toe pushing off, what detect_foot_contacts calls a
// contact), breaks of up to max_gap_seconds filled. Within a stance each frame step takes out what the foot's
// planted joints move beyond what they may (`drift`; without it, nothing), their steps averaged
// weighted by how near each is to its floor (a lifting heel leaves the toe to hold the foot), so
// the foot moves as it may and never faster than it did; the stance's offsets have a mean of zero
// (the least total correction). The offset changes from one stance to the next; between stances the
// change is spread over the whole swing, each step's share a bump that is zero at landing and
// lift-off (no jump in speed there) times the room that step leaves under the limit's fastest
// joint (the foot's own speed taken off): the change goes where the swinging foot is slow, not
// mid-swing where it is at its fastest; before the first stance and after the last it fades over
// blend_frames(). Each such frame moves the ankle horizontally (its height kept, so the same
// steps stay planted) with analytic two-bone IK: the hip stays, thigh and shin keep their
// lengths, the knee bends in the plane of hip, target and the knee's own offset from its
// hip-ankle line, leaning slightly towards the toe (less as the knee bends or the ankle moves
// less) and, where the knee is nearly straight, towards its bend on the frame before; a target
// beyond the leg's reach is shortened to it (a straight leg stays as straight), and what the
// reach held back is caught up gradually. Where fully pinned targets would be beyond reach (a
// content standing on straight legs, a style swaying its hips over them), the whole body above
// the knees first comes down as far as they need, at most kMaxBodyDrop of the leg, smoothed over
// blend_frames() either side so it never pops, the knees bending to keep the feet where they are. The toe moves with the ankle (the foot is
// translated). Frames beyond the fades are left exactly as they were. A leg whose planted joints
// would move more in all than before the lock is left as it was: the measure never rises.
// drift: when given (F x 2 kFootJoints, x and z per foot joint in planted_feet.h's order, world
// units), how far each planted foot joint may move from frame t to t + 1 (what the mixed takes'
// own planted feet do: a foot that pivots or rolls in the takes); none: planted feet are held
// still. A motion whose planted feet move exactly as allowed (a take on its own) is left as it
// is. Throws InputError on a shape mismatch or a rig without a body height. O(F), no allocation
// once scratch has size F.
// limits: see FootLockLimits; with planted_speed the lock may try up to seven times.
// held: when given (F x kFootJoints, planted_feet.h's order), 1 where the takes mixed plant that
// foot joint (read only for the joints the rig has): a foot is pinned over those frames too (a
// foot the takes stand on, which the mix lifts before it comes down, is held over its spot, not
// eased towards its next stance).
void apply_foot_lock(Eigen::MatrixXd& world, const FootRig& rig, FootLockScratch& scratch,
                     const Eigen::MatrixXd* drift = nullptr, const FootLockLimits& limits = {},
                     const Eigen::MatrixXd* held = nullptr);

}  // namespace mostyle
