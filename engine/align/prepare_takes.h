#pragma once
// The first stage of the one chain (any number of takes, one code path), for 2 to 16 takes of one action; take 0 is the
// reference, whose skeleton, bones, world and timeline the others are brought onto:
//   each take, once: its major joints at the working rate (FK), retargeted onto the reference's
//   bones (the reference as it is), in the canonical frame (canonical_frame.h), its foot contacts
//   and cycles (its own rate's, carried over, where the working rate's frames miss a strike);
//   each other take: registered onto the reference by cycles when both repeat (its cycles laid
//   on the reference's, its posture in between: cycle_registration.h; its own timeline is then
//   the registered one, which covers the whole reference), else aligned whole (left-foot DTW or
//   the smooth warp, alignment.h); placed where the reference stands when their match starts;
//   all of them read on one common timeline (U samples, common_timeline.h): poses, root paths
//   and steps, whole-turn flips, contacts, then normalized: each take less its own
//   mean pose, all divided by one scale (the spread of every take's centred values).
// A pair is two takes: its common timeline is the alignment's own warp, unchanged. The
// decomposition (decompose_takes.h) and the synthesis (mix_palette.h) read this value; nothing here
// knows of them.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "engine/align/alignment.h"
#include "engine/align/cycle_slots.h"
#include "engine/align/cycles.h"
#include "engine/align/common_timeline.h"
#include "engine/base/clip.h"
#include "engine/base/job_control.h"
#include "engine/base/stage_times.h"
#include "engine/measure/foot_contact.h"
#include "engine/measure/fastest_joint.h"
#include "engine/measure/planted_feet.h"
#include "engine/prepare/canonical_frame.h"
#include "engine/prepare/major_skeleton.h"
#include "engine/prepare/root_path.h"

namespace mostyle {

constexpr int kMaxPaletteTakes = 16;

struct PrepareOptions {
  double fps = 30.0;      // working and output frame rate; 0 keeps the reference's own rate
  AlignmentOptions align;  // DTW method, feature, slope limit, open ends (align/alignment.h)
  MappingOverrides mapping_a;  // the reference's joints; empty: name rules only
  MappingOverrides mapping_b;  // the second take's (take 1) joints
  FootContactOptions foot_contacts;  // detection thresholds and the lock's fade (foot_contact.h)
  // Non-empty: only these canonical joints (major_skeleton.h), of those the takes share, so that
  // two of a palette's takes prepared on their own have the palette's joints.
  std::vector<int> only_majors;
  void Validate() const;  // throws InputError on a bad fps or alignment option
};

// One take. Its own frames (F, at the working rate) are in the reference's bones; on the
// common timeline (U samples) in the reference's world. A take registered by cycles has as its
// own frames the registered take (F = V frames, `registration` says which of its file's frames
// each shows).
struct PreparedTake {
  std::shared_ptr<const Clip> clip;  // as loaded
  MajorMapping mapping;
  std::vector<std::string> names;    // the file's names of the shared joints
  // Its own timeline.
  Eigen::MatrixXd world;             // F x 3M: retargeted onto the reference's bones, its own world
  Eigen::MatrixXd world_placed;      // F x 3M: the same moved rigidly so its matched start is the reference's (ghosts)
  CanonicalMotion canonical;         // F frames
  Eigen::MatrixXd own_local_t;       // 3M x F: canonical.local transposed (a frame a contiguous column, for the mix)
  Eigen::MatrixXd own_contacts;      // F x 2: foot contacts, left and right, 1 planted
  // How fast its planted feet move (planted_feet.h) on its own frames as loaded, retargeted
  // (before any registration), in the reference's units: what outputs are measured against.
  PlantedSpeed planted;
  // Its fastest joint's speed (fastest_joint.h) on the same frames, units per second: what an
  // output's joints are held under (the foot lock's swings, no pops).
  double fastest_joint = 0.0;
  // F x 2 kFootJoints: each foot joint's travel while planted (planted_feet.h, in a band twice the
  // measure's; x, z per joint in kFootJoints order) from the first frame, summed over the steps
  // f -> f + 1 where it is planted at both ends, each in the body's frame at f (turned by
  // -heading[f]): the planted move from
  // frame a to b in the body's frame is row b minus row a (what the foot lock lets a planted foot
  // of an output do, mix_palette.cpp planted_drift).
  Eigen::MatrixXd foot_travel;
  // F x kFootJoints: each foot joint's height (planted_feet.h's order; 0 for a joint the rig
  // lacks), on its own frames, file units: where an output of it keeps the foot planted or in the
  // air (mix_palette.cpp feet_heights).
  Eigen::MatrixXd foot_height;
  TakeCycles cycles;                 // where it repeats, as detected on its file's frames (cycles.h)
  CycleRegistration registration;    // by cycles onto the reference: its cycles, sources, spans; empty otherwise
  Alignment alignment;               // onto the reference (the reference's own: empty)
  // The common timeline.
  Eigen::VectorXd frames;            // U: the take's frame at each sample (fractional)
  Eigen::MatrixXd local;             // U x 3M canonical poses
  Eigen::MatrixXd ground;            // U x 2 hips ground path, placed at the reference's start
  Eigen::MatrixXd steps;             // U x 3 root steps (root_path.h)
  Eigen::VectorXd turn_flips;        // U: whole turns match_turns adds to keep its facing near the reference's
  Eigen::MatrixXd contacts;          // U x 2 foot contacts carried onto the timeline
  Eigen::RowVectorXd mean;           // normalization: the take's mean pose
  Eigen::MatrixXd x;                 // U x 3M normalized: (local - mean) / scale
  // Its cycles on its own timeline as prepared: the registered ones when registered by cycles.
  const TakeCycles& timeline_cycles() const { return registration.empty() ? cycles : registration.cycles; }
};

struct PreparedTakes {
  std::vector<PreparedTake> takes;   // takes[0]: the reference
  CommonTimeline timeline;
  std::vector<int> majors, parents;  // shared joints (M) and their parents within them
  std::vector<double> lengths;       // the reference's bone lengths per joint, its units
  FootRig feet;                      // leg columns, leg length, contact thresholds
  FeatureJoints feature_joints;      // the columns the alignment's feature reads
  double fps = 30.0;                 // working rate
  double scale = 1.0;                // normalization scale, shared by every take
  Eigen::VectorXd reference_heading; // U: the reference's heading at each sample (a mix starts facing it)
  // The reference's cycles as slots every take registered by cycles fills (cycle_slots.h): as
  // many as the most cycles of any take, the reference's own timeline extended with replays of
  // its last cycles where it has fewer (extend_by_cycles); empty when no take is registered by
  // cycles.
  CycleSlots slots;
  int samples() const { return timeline.samples(); }
  int size() const { return static_cast<int>(takes.size()); }
  const PreparedTake& reference() const { return takes.front(); }
};

// clips: 2 to 16 takes, the first the reference. Throws InputError (naming the take when there
// are more than two) on a count out of range, takes without the major joints the reference has,
// no frames, degenerate hips, bad options; Cancelled. Cost: FK O(frames x joints) per take, one
// DTW O(F0 x Fi) per other take, then O(U x N x M). times: when given, its preprocess_ms and
// dtw_ms are set (summed over the takes).
std::shared_ptr<const PreparedTakes> prepare_takes(const std::vector<std::shared_ptr<const Clip>>& clips,
                                                   const PrepareOptions& options, JobControl* control = nullptr,
                                                   StageTimes* times = nullptr);

// The cycles of one take on its own, in its file's frames, as prepare_takes finds them for a
// reference at its own rate, from its feet's signals: FK of the hips and legs only, their bones,
// the feet, canonical frame, contacts and cycles (the rest of the body only for a take whose feet
// give no gait, for periodic cycles). Throws InputError as prepare_takes does (a take without the
// major joints). Cost: O(F x joints on the legs' chains) plus detect_foot_contacts and
// detect_cycles.
TakeCycles take_cycles(const std::shared_ptr<const Clip>& clip);

// The reference's joint index of each major column (for export).
std::vector<int> export_joints(const PreparedTakes& prepared);

// Take i's frames on its own timeline (fractional, K values: a mix's sources) as its file's frames
// at the working rate: unchanged for a take aligned whole; through its registration for one
// registered by cycles, NaN where it gives its posture only. O(K).
Eigen::VectorXd frames_in_take(const PreparedTake& take, const Eigen::VectorXd& frames);

// Which of take i's own cycles each of `frames` (its timeline's) shows, -1 outside them: an index
// in registration.take_cycles for a take registered by cycles, in `cycles` for one aligned whole.
// O(K log cycles).
Eigen::VectorXi cycles_shown(const PreparedTake& take, const Eigen::VectorXd& frames);

}  // namespace mostyle
