#pragma once
// Foot contacts (beyond the paper): when each foot is planted in a take, carried through the DTW
// onto A's timeline and blended; the foot lock (post/foot_lock.h) pins the planted feet of a mix
// so it does not skate. Works on major-joint positions (frames x 3M, file units, Y up), the same
// matrices the pipeline blends.
#include <Eigen/Core>
#include <array>
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
  int max_gap_frames() const;      // options.max_gap_seconds at fps, rounded down
  // Throws InputError, `where` first, when world (F x 3M) has too few columns for a leg's joint.
  void check_columns(const Eigen::MatrixXd& world, const char* where) const;
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
// plant at different moments; the foot lock would pin each flicker's stances apart. O(F), in place.
void tidy_contacts(Eigen::MatrixXd& contacts, const FootRig& rig);

// B's contacts (Fb x 2) carried onto A's timeline: row i is B's row at warp(i) rounded (warp:
// dtw.h warp_map, F values in B's frames). Throws InputError on an empty B. O(F).
Eigen::MatrixXd carry_contacts(const Eigen::MatrixXd& contacts_b, const Eigen::VectorXd& warp);

// Frames where a foot lands: contacts(f, foot) planted and not at f - 1 (never frame 0: a take
// that starts planted has not struck). contacts: F x 2, 1 planted. O(F).
std::vector<int> foot_strikes(const Eigen::MatrixXd& contacts, int foot);

}  // namespace mostyle
