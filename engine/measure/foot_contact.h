#pragma once
// Foot contacts (beyond the paper): when each foot is planted in a take, carried through
// the DTW onto A's timeline and blended, and a foot lock that pins planted feet in place with
// two-bone IK (hip-knee-ankle) so the blend does not skate. Works on major-joint positions
// (frames x 3M, file units, Y up), the same matrices the pipeline blends.
#include <Eigen/Core>
#include <array>
#include <utility>
#include <vector>

namespace mostyle {

// Columns (within the major-joint positions) of one leg; -1 where the take has none.
struct LegColumns {
  int hip = -1, knee = -1, ankle = -1, toe = -1;
  bool usable() const { return hip >= 0 && knee >= 0 && ankle >= 0; }
};

// Thresholds are relative to the skeleton (its leg length), so they hold in any unit.
struct FootContactOptions {
  double height_fraction = 0.06;      // ankle at most this many leg lengths above its floor level
  double speed_fraction = 0.45;       // ankle slower than this many leg lengths per second
  double min_contact_seconds = 0.05;  // shorter contacts are dropped (noise); a run stands 0.1-0.25 s
  double max_gap_seconds = 0.07;      // shorter breaks inside a contact are filled
  double blend_seconds = 0.15;        // the lock fades in before the first contact, out after the last
  void Validate() const;              // throws InputError on a negative or non-finite value
};

// What contact detection and the lock need to know about the takes, fixed in prepare_takes.
struct FootRig {
  std::array<LegColumns, 2> legs;  // 0: left, 1: right
  double leg_length = 0.0;         // thigh + shin, averaged over the legs, file units
  double body_height = 0.0;        // the reference's standing height (planted_feet.h standing_height), file units
  double fps = 30.0;               // frame rate of the positions
  FootContactOptions options;
  int blend_frames() const;        // options.blend_seconds at fps, at least 1
};

// The legs' columns from the major joints present (canonical order, major_skeleton.h), the leg
// length and the body's height from per-joint bone lengths (bone_lengths(), parallel to majors). Throws InputError
// on bad options or a zero fps.
FootRig make_foot_rig(const std::vector<int>& majors, const std::vector<double>& lengths, double fps,
                      const FootContactOptions& options = {});

// Contacts of one take: F x 2 (left, right foot), 1 where the ankle is within height_fraction
// of its floor level (the 5th percentile of its height within 0.75 s of the frame, taken every
// 0.1 s, so a floor that rises or falls over the take is followed) and slower than
// speed_fraction (a landing cut short by the take's last frame: three times that), after gaps are
// filled and short contacts dropped; 0 elsewhere. world: F x 3M. A take whose hips stay in place
// (their ground point travels slower than 0.2 leg lengths per second: a game's walk or run loop)
// slides its planted foot backwards under the body: its ankles' speeds are measured, in the
// body's frame, against that "belt" (the median velocity of the ankle while it is low) and
// allowed half the belt's speed when that is more; a take that travels is measured as it is.
// loop_frames: L > 0 for a loop clip (cycles.h TakeCycles::loop_frames): the take is read as
// played on repeat (frame f + L is frame f moved on by the loop's travel and turn), so a contact
// across its end is one contact and frame f's speed at either end is measured across the seam.
// A leg that is not usable is never in contact. Throws InputError on a column mismatch or a loop
// longer than the take. O(F x w) (w: the floor's window in frames); three times F for a loop.
Eigen::MatrixXd detect_foot_contacts(const Eigen::MatrixXd& world, const FootRig& rig, int loop_frames = 0);

// Contacts (F x 2, 1 planted) tidied in place as detection tidies them: breaks of at most
// max_gap_seconds between two contacts filled, then contacts shorter than min_contact_seconds
// (at rig.fps, to the nearest frame) dropped, but for one that the take's first or last frame
// cuts (it may have lasted longer: a landing in the last frames is a foot strike). A mix's contacts (weighted, then thresholded) can flicker where the takes
// plant at different moments; the foot lock would pin each flicker's runs apart. O(F), in place.
void tidy_contacts(Eigen::MatrixXd& contacts, const FootRig& rig);

// B's contacts (Fb x 2) carried onto A's timeline: row i is B's row at warp(i) rounded (warp:
// dtw.h warp_map, F values in B's frames). Throws InputError on an empty B. O(F).
Eigen::MatrixXd carry_contacts(const Eigen::MatrixXd& contacts_b, const Eigen::VectorXd& warp);

// Frames where a foot lands: contacts(f, foot) planted and not at f - 1 (never frame 0: a take
// that starts planted has not struck). contacts: F x 2, 1 planted. O(F).
std::vector<int> foot_strikes(const Eigen::MatrixXd& contacts, int foot);

// Buffers apply_foot_lock reuses, so the lock does not allocate once they have the right size.
struct FootLockScratch {
  Eigen::VectorXd weight;  // F: 1 where the ankle is moved, 0 where it is left as it is
  Eigen::MatrixXd target;  // F x 2: the horizontal offset (x, z) that moves it
  Eigen::MatrixXd planted; // F x 4: planted_feet.h's planted frames
  Eigen::VectorXi pinned;  // F: 1 on the frames a foot is pinned over
  Eigen::VectorXd ease;    // F: after a run, how far its offset has eased to the next (-1 elsewhere)
  Eigen::VectorXd swing;   // F: within a swing, how far the offset has gone from one run's to the next's
  Eigen::VectorXd yaw;     // F: the turn (radians about the vertical) that holds a planted foot's heading
  Eigen::MatrixXd before;  // F x 9: a leg's knee, ankle and toe as they were
  std::vector<double> heights;
  std::vector<std::pair<Eigen::Index, Eigen::Index>> runs;  // a leg's runs, first and last frame
  // F x 18: the legs' knees, ankles and toes as they were, and in the best try, where the lock
  // tries again.
  Eigen::MatrixXd original, best;
  // F x 15, a frame a row: both hips and one leg's knee, ankle and toe, as the lock moves the leg.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> leg_rows;
  std::array<double, 2> before_moves{};  // per leg: its planted joints' moves before the lock
  const Eigen::MatrixXd* held = nullptr;  // apply_foot_lock's, for its tries
};

// What the lock keeps an output under, from the takes it mixes (0: no limit), units per second.
struct FootLockLimits {
  // No step of a swing or fade is made faster than this by the change of offset it carries (each
  // foot joint's own speed plus that change): the runs on either side are pinned in part instead
  // (the mixed takes' fastest joint, fastest_joint.h: no pops).
  double fastest_joint = 0.0;
  // With a drift: where allowing all of it leaves the planted feet (planted_feet.h's measure)
  // faster than this, less of it is allowed, down to none (the takes' own planted feet, weighted).
  double planted_speed = 0.0;
};

// Locks planted feet in place, in world (F x 3M) itself. A foot is pinned over runs of frames
// where one of its joints is planted by planted_feet.h's measure (within a band of its floor: a
// heel coming down, a toe pushing off, what detect_foot_contacts calls a contact), breaks of up
// to max_gap_seconds filled. Within a run each frame step takes out what the foot's
// planted joints move beyond what they may (`drift`; without it, nothing), their steps averaged
// weighted by how near each is to its floor (a lifting heel leaves the toe to hold the foot), so
// the foot moves as it may and never faster than it did; the run's offsets have a mean of zero
// (the least total correction). The offset changes from one run to the next; between runs the
// change is spread over the whole swing, each step's share a bump that is zero at landing and
// lift-off (no jump in speed there) times the room that step leaves under the limit's fastest
// joint (the foot's own speed taken off): the change goes where the swinging foot is slow, not
// mid-swing where it is at its fastest; before the first run and after the last it fades over
// blend_frames(). Each such frame moves the ankle horizontally (its height kept, so the same
// steps stay planted) with analytic two-bone IK: the hip stays, thigh and shin keep their
// lengths, the knee bends in the plane of hip, target and the knee's own offset from its
// hip-ankle line, leaning slightly towards the toe (less as the knee bends or the ankle moves
// less) and, where the knee is nearly straight, towards its bend on the frame before; a target
// beyond the leg's reach is shortened to it (a straight leg stays as straight), and what the
// reach held back is caught up gradually. The toe moves with the ankle (the foot is
// translated). Frames beyond the fades are left exactly as they were. A leg whose planted joints
// would move more in all than before the lock is left as it was: the measure never rises.
// drift: when given (F x 2 kFootJoints, x and z per foot joint in planted_feet.h's order, world
// units), how far each planted foot joint may move from frame t to t + 1 (what the mixed takes'
// own planted feet do: a foot that pivots or rolls in the takes); none: planted feet are held
// still. A motion whose planted feet move exactly as allowed (a take on its own) is left as it
// is. Throws InputError on a shape mismatch or a rig without a body height. O(F), no allocation
// once scratch has size F.
// limits: see FootLockLimits; with planted_speed the lock may run up to seven times.
// held: when given (F x kFootJoints, planted_feet.h's order), 1 where the takes mixed plant that
// foot joint (read only for the joints the rig has): a foot is pinned over those frames too (a
// foot the takes stand on, which the mix lifts before it comes down, is held over its spot, not
// eased towards its next run).
void apply_foot_lock(Eigen::MatrixXd& world, const FootRig& rig, FootLockScratch& scratch,
                     const Eigen::MatrixXd* drift = nullptr, const FootLockLimits& limits = {},
                     const Eigen::MatrixXd* held = nullptr);

// One two-bone IK solve, exposed for tests: hip, knee, ankle are the chain's joints, `target`
// where the ankle should go. Returns the new knee and ankle (hip unchanged); thigh |knee - hip|
// and shin |ankle - knee| keep their lengths. `bend_fallback` is used as the knee's bend
// direction when the leg is straight (knee on the hip-target line).
void two_bone_ik(const Eigen::Vector3d& hip, const Eigen::Vector3d& knee, const Eigen::Vector3d& ankle,
                 const Eigen::Vector3d& target, const Eigen::Vector3d& bend_fallback,
                 Eigen::Vector3d* new_knee, Eigen::Vector3d* new_ankle);
// The same with the bend direction taken from `pole` (its part perpendicular to hip-target)
// instead of from the knee; bend_fallback where that part vanishes.
void two_bone_ik_pole(const Eigen::Vector3d& hip, const Eigen::Vector3d& knee, const Eigen::Vector3d& ankle,
                      const Eigen::Vector3d& target, const Eigen::Vector3d& pole, const Eigen::Vector3d& bend_fallback,
                      Eigen::Vector3d* new_knee, Eigen::Vector3d* new_ankle);

}  // namespace mostyle
