#pragma once
// Registration by cycles: which cycle of another take each cycle of the reference is matched
// with, and the take laid on the reference's cycles accordingly.
// A take with fewer cycles than the reference has its cycles reused in order (its first, its
// second, ..., its last, its first again), so that its own cycle-to-cycle variation is kept and
// the reference is covered whole, however short the take. Frames of the reference outside its
// cycles (standing, a start, a stop, a turn on the spot) have no match: there the other take is
// to give its posture only.
#include <Eigen/Core>
#include <vector>

#include "engine/align/cycles.h"
#include "engine/prepare/canonical_frame.h"

namespace mostyle {

// For each cycle of the reference, the index of the take's cycle matched with it; empty when
// either has no cycles. The take's cycles in order, then, where the reference has more, its last
// cycles again in order, ending on its last (replay_cycle): the slots past the take's own hold
// cycles it has already played, so that a mix at the take's weight 1 skips them and plays its
// own cycles once each, its stop after its last (mixed_clock.h).
std::vector<int> pair_cycles(const TakeCycles& reference, const TakeCycles& take);

// The cycle of n a take shows at slot k of `slots` (slots >= n, k < slots): its own k below n,
// then its last slots - n cycles again in order (from the first again where it has fewer), so
// that the last slot shows its last cycle and its stop follows on.
int replay_cycle(int k, int n, int slots);

// The take registered onto the reference by cycles: a motion of V frames laid on the
// reference's spans, in order. A span of the reference inside its cycle k holds the take's cycle
// pairs[k], its own frames (V frames as many as that cycle has, so its timing is the take's); a
// span outside the reference's cycles holds, frame for frame, the reference's own motion moved
// by the take's posture (the take's mean pose over its cycles minus the reference's), faded
// over up to fade frames into the take's own frames running on from the cycle before and into
// the cycle after. The reference's start (before its first cycle) and stop (after its last)
// hold the take's own start and stop instead, in its timing, where both takes are alike there
// (both under way, or both starting or stopping from standing; the reference's last cycle holds
// the take's last, pair_cycles): at weight 1 the walk begins and ends as the take's does. Edges
// within 1.5 times each other's length are matched as cycles are; longer ones frame for frame
// next to the cycle and, beyond, a hold of the shorter one (Anchor::hold). Where a reused cycle does not follow on from the one before in the take (its
// last cycle, then its first again), the pose difference at the seam is spread over the cycle
// (full at its start, none at its end). The root steps follow the same rule (the take's in its
// cycles, the reference's in between) and are integrated from the reference's first frame.
struct CycleRegistration {
  TakeCycles take_cycles;             // the take's own cycles it was registered with, in its frames
  std::vector<int> pairs;             // per reference cycle, the take's cycle (pair_cycles)
  TakeCycles cycles;                  // the registered cycles, in the registered frames, one per reference cycle
  // Where the spans meet: the reference's frame and the registered frame at each span's start,
  // then both ends' last frames (cycle false). From an anchor to the next the frames run 1:1 (a
  // span outside cycles), cover a reference cycle and its take cycle (cycle true), or one of the
  // two holds its frame while the other plays on (hold true: a start or stop far longer in one).
  struct Anchor {
    int reference = 0, registered = 0;
    bool cycle = false;
    bool hold = false;
  };
  std::vector<Anchor> anchors;
  Eigen::VectorXd source;             // V: the take's own frame each registered frame shows; NaN: its posture only
  Eigen::VectorXi source_cycle;       // V: which of the take's cycles that frame is from; -1 outside them
  // No registration (the take aligned whole). One without pairs but with anchors lays the take's
  // posture alone on a reference that has no cycles (register_posture_only).
  bool empty() const { return pairs.empty() && anchors.empty(); }
  bool posture_only() const { return !anchors.empty() && pairs.empty(); }
};

struct RegisteredMotion {
  CanonicalMotion motion;        // V frames: local (V x 3M), ground (V x 2), heading (V)
  Eigen::MatrixXd contacts;      // V x 2
  CycleRegistration registration;
};

// The reference laid on `slots` cycles (more than its own, a take registered with it has more):
// its own frames, and before its stop its last slots - cycles cycles again (replay_cycle), each
// replay's seam with the cycle before it (the pose at its end against its start) spread over it
// (full at its start, none at its end), its root's steps its own. So another take's extra cycles
// have cycles of the reference to be registered on, and a mix at the reference's weight 1 skips
// the replays and shows its own frames in order (mixed_clock.h). The registration's source is
// the reference's own frame at each frame, pairs the slots' cycles, cycles the slots in the
// extended frames; motion, contacts and root V frames, the root integrated from its first frame.
// Throws InputError on cycles that do not fit the frames, or slots not above the cycles.
// O(V x 3M).
RegisteredMotion extend_by_cycles(const CanonicalMotion& motion, const Eigen::MatrixXd& contacts,
                                  const TakeCycles& cycles, int slots);

// Whether two takes can be registered by cycles: both have cycles of one kind, and gait cycles
// begin at the same foot's strikes (detect the take's again with CycleOptions::foot otherwise).
bool cycles_register(const TakeCycles& reference, const TakeCycles& take);

// The take registered onto the reference (see RegisteredMotion). reference/take: canonical
// motions (Fr and Ft frames, one skeleton), their contacts (F x 2) and cycles (cycles_register
// true); fade: frames over which the take's own frames fade into its posture, from each cycle.
// Throws InputError when the cycles cannot be registered or do not fit their takes' frames.
// O((Fr + V) x 3M).
RegisteredMotion register_by_cycles(const CanonicalMotion& reference, const Eigen::MatrixXd& reference_contacts,
                                    const TakeCycles& reference_cycles, const CanonicalMotion& take,
                                    const Eigen::MatrixXd& take_contacts, const TakeCycles& take_cycles, int fade);

// The mean pose (a row of local, F x 3M) over the frames of a take's cycles; a loop's cycle may be
// read across its end (frame f + L shows frame f), another's past the last frame holds it. The
// zero row when there are no cycles. O(cycle frames x 3M).
Eigen::RowVectorXd cycles_mean_pose(const Eigen::MatrixXd& local, const TakeCycles& cycles);

// What a take gives where it gives its posture only: its mean pose and how far each joint moves
// about it, over its cycles for a take that walks (a loop's read across its end, as
// cycles_mean_pose), over all of its frames otherwise. The spread is the style's size of
// movement (an exhausted wave's small strokes, a proud walk's wide arm swing), which a posture
// alone leaves out. O(frames x 3M).
struct TakePosture {
  Eigen::RowVectorXd mean;    // 3M: the mean pose (a row of local)
  Eigen::RowVectorXd spread;  // M: each joint's RMS distance from its mean position
  Eigen::RowVectorXd fastest; // M: each joint's largest move from one frame to the next (of all frames)
};
TakePosture take_posture(const Eigen::MatrixXd& local, const TakeCycles& cycles);

// A take laid on a reference it has no part to match with: a walk on a reference that does not
// walk (standing, a jump, a wave), or a take that does not walk (a wave, a bow, a kick) on a
// walking reference. No frame of the take matches one of the reference's, so it gives its
// posture only, throughout, as a walk does between the reference's cycles: the reference's own
// motion (its poses, root and contacts) moved by the take's mean pose minus the reference's (both
// take_posture; the reference's over all of its frames), and, for the joints `sized` marks (M;
// the legs carry the reference's steps, so they keep their motion), the reference's movement about
// its mean scaled by the take's spread over the reference's, at least spread_floor (so a joint
// the reference holds still moves less than the take's at most), and never so much that it moves
// faster than the take's fastest (no pop where a small swing is sized up). With the reference's own
// posture nothing changes. Frames run 1:1 (anchors at both ends); every source is NaN.
// reference: Fr frames; take_cycles: the take's, kept in the registration. Throws InputError on
// mismatched sizes or a spread floor not above 0. O(Fr x 3M).
RegisteredMotion register_posture_only(const CanonicalMotion& reference, const Eigen::MatrixXd& reference_contacts,
                                       const TakePosture& take, const TakeCycles& take_cycles,
                                       const std::vector<bool>& sized, double spread_floor);

}  // namespace mostyle
