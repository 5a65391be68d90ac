#include "engine/align/prepare_takes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>

#include "engine/align/cycle_phase.h"
#include "engine/base/clock.h"
#include "engine/base/error.h"
#include "engine/kinematics/limb_length.h"
#include "engine/prepare/major_take.h"
#include "engine/prepare/retarget.h"

namespace mostyle {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kMaxFps = 1000.0;
// The posture of a take registered by cycles fades in and out over this many of the
// reference's cycles, where the reference is not in a cycle.
constexpr double kPostureFadeCycles = 0.5;
// A take that gives its posture only sizes the reference's movement about its mean by its own
// spread over the reference's, the reference's taken as at least this many leg lengths: a joint
// the reference barely moves then moves by at most the take's spread, never its jitter scaled up.
constexpr double kPostureSpreadFloor = 0.05;
// A take's planted travel (foot_travel) counts its foot joints' steps within this many of the
// measure's bands of their floor: an output planted where a take's foot is just above the band
// (their floors differ a little, as their frames do) may move as that foot does. The lock keeps
// the output's measure to the takes' own as a whole (FootLockLimits::planted_speed).
constexpr double kTravelBandScale = 2.0;
// A take's cycle moved to begin at the other foot's strike may lose this fraction of itself at the
// take's first or last frame (cycles_from_other_foot).
constexpr double kOtherFootClip = 0.1;

std::string take_name(int i, const Clip& clip) {
  return "take " + std::to_string(i + 1) + " (" + clip.source + ")";
}

// How an alignment's warnings name a take: A and B for two takes (as the editor shows a pair),
// its file's name for more; frames are counted as its file counts them.
AlignedTake aligned_name(int i, int takes, const Clip& clip) {
  if (takes == 2) return {i == 0 ? "A" : "B", clip.fps()};
  return {std::filesystem::path(clip.source).filename().string(), clip.fps()};
}

// The canonical joints every take shares with the reference; the mapping overrides name the
// reference's joints and the second take's.
std::vector<int> shared_majors(const std::vector<std::shared_ptr<const Clip>>& clips,
                               const std::vector<MajorMapping>& mappings, const std::vector<int>& only) {
  const int n = static_cast<int>(clips.size());
  std::vector<int> common;
  for (int i = 1; i < n; ++i) {
    std::vector<int> shared;
    try {
      shared = shared_major_joints(mappings[0], clips[0]->source, mappings[i], clips[i]->source);
    } catch (const InputError& e) {
      if (n == 2) throw;
      throw InputError(take_name(i, *clips[i]) + ": " + e.what());
    }
    if (i == 1) common = shared;
    else common.erase(std::remove_if(common.begin(), common.end(),
                                     [&](int m) { return std::find(shared.begin(), shared.end(), m) == shared.end(); }),
                      common.end());
  }
  if (!only.empty())
    common.erase(std::remove_if(common.begin(), common.end(),
                                [&](int m) { return std::find(only.begin(), only.end(), m) == only.end(); }),
                 common.end());
  return common;
}

// The joints of a take's canonical poses that the gait checks read: the hips (column 0, as
// to_canonical is given it) and the ankles.
GaitJoints gait_joints(const FootRig& feet) {
  GaitJoints joints;
  joints.hips = 0;
  for (int side = 0; side < 2; ++side) joints.ankles[static_cast<size_t>(side)] = feet.legs[static_cast<size_t>(side)].ankle;
  return joints;
}

// The columns of a take's canonical poses its feet's signals are read from: the hips (column 0)
// and each usable leg's joints, in column order.
std::vector<int> feet_signal_columns(const FootRig& feet) {
  std::vector<int> columns{0};
  for (const LegColumns& leg : feet.legs)
    for (int c : {leg.hip, leg.knee, leg.ankle, leg.toe})
      if (c > 0) columns.push_back(c);
  std::sort(columns.begin(), columns.end());
  columns.erase(std::unique(columns.begin(), columns.end()), columns.end());
  return columns;
}

// Those columns of local (F x 3M), and where the gait checks' joints are among them.
Eigen::MatrixXd feet_signals(const Eigen::MatrixXd& local, const FootRig& feet, GaitJoints* joints) {
  const std::vector<int> columns = feet_signal_columns(feet);
  Eigen::MatrixXd out(local.rows(), 3 * static_cast<Eigen::Index>(columns.size()));
  for (size_t k = 0; k < columns.size(); ++k) out.middleCols(3 * static_cast<Eigen::Index>(k), 3) = local.middleCols(3 * columns[k], 3);
  auto at = [&](int c) {
    const auto it = std::find(columns.begin(), columns.end(), c);
    return c >= 0 && it != columns.end() ? static_cast<int>(it - columns.begin()) : -1;
  };
  const GaitJoints all = gait_joints(feet);
  joints->hips = at(all.hips);
  for (size_t side = 0; side < 2; ++side) joints->ankles[side] = at(all.ankles[side]);
  return out;
}

// A take's cycles from its feet's signals: the loop and the gait cycles are read on the hips
// and legs alone (what take_cycles computes, with no FK of the rest); only where the feet give no
// gait is the whole pose read, for periodic cycles (whole_local: the take's F x 3M canonical
// poses, asked for then only). contacts: the take's, detected with the loop read on the legs.
TakeCycles cycles_from_feet(const Eigen::MatrixXd& contacts, const Eigen::MatrixXd& legs_local,
                            const GaitJoints& legs_joints, const FootRig& feet, const CycleOptions& options,
                            const std::function<const Eigen::MatrixXd&()>& whole_local) {
  TakeCycles cycles = detect_cycles(contacts, legs_local, feet.fps, feet.leg_length, options, legs_joints);
  if (cycles.kind == CycleKind::kGait) return cycles;
  return detect_cycles(contacts, whole_local(), feet.fps, feet.leg_length, options, gait_joints(feet));
}

// A take's foot contacts and cycles on its own frames (world F x 3M, canonical its canonical
// frame, at feet.fps): a loop clip's contacts are read across its end.
// majors: the canonical joint of each column, which names the body part that moves most.
void contacts_and_cycles(const Eigen::MatrixXd& world, const CanonicalMotion& canonical, const FootRig& feet,
                         const std::vector<int>& majors, Eigen::MatrixXd* contacts, TakeCycles* cycles) {
  GaitJoints joints;
  const Eigen::MatrixXd legs = feet_signals(canonical.local, feet, &joints);
  *contacts = detect_foot_contacts(world, feet, cycle_loop_frames(legs, feet.fps, feet.leg_length));
  *cycles = cycles_from_feet(*contacts, legs, joints, feet, {}, [&]() -> const Eigen::MatrixXd& { return canonical.local; });
  // Gait's spans are read on the legs' columns alone; another action's on the whole pose.
  const int mover = cycles->spans.mover;
  if (cycles->kind != CycleKind::kGait && mover >= 0 && mover < static_cast<int>(majors.size()))
    cycles->spans.mover_part = body_part_of(major_joint_name(majors[static_cast<size_t>(mover)]));
}

// A take whose gait cycles begin at one foot's strikes, with too few strikes of the other foot for
// a whole cycle between two of them (a one-cycle take: each foot strikes once or twice): its
// cycles begun at `foot`'s strike inside each instead, each as long as the cycle it comes from,
// ending at that strike (the cycle before it) or beginning there, whichever the take's frames
// hold with at most kOtherFootClip of it cut off at the take's end (the cut cycle begins a few
// frames after the strike or ends a few frames short of the next). None when neither fits.
// cycles: gait cycles (TakeCycles::foot the other foot); contacts: F x 2. O(F).
TakeCycles cycles_from_other_foot(const TakeCycles& cycles, const Eigen::MatrixXd& contacts, int foot, int frames) {
  TakeCycles out = cycles;
  out.cycles.clear();
  out.foot = foot;
  out.strike_phase = 0.0;
  if (cycles.kind != CycleKind::kGait || cycles.loops() || foot < 0) return out;
  const std::vector<int> strikes = foot_strikes(contacts, foot);
  for (const Cycle& c : cycles.cycles) {
    for (int s : strikes) {
      if (s <= c.begin || s >= c.end) continue;
      const int length = c.frames(), most_cut = static_cast<int>(kOtherFootClip * length);
      const Cycle before{std::max(0, s - length), s}, after{s, std::min(frames - 1, s + length)};
      const Cycle& pick = before.frames() >= after.frames() ? before : after;
      if (length - pick.frames() <= most_cut &&
          (out.cycles.empty() || out.cycles.back().end <= pick.begin))
        out.cycles.push_back(pick);
      break;
    }
  }
  if (out.cycles.empty()) {
    out.kind = CycleKind::kNone;
    out.reason = "no whole gait cycle begins at the other foot's strikes";
  }
  return out;
}

// A take's cycles as registration needs them: gait cycles beginning at the foot the reference's
// begin at (detected again at that foot when the take's own begin at the other); none when the
// alignment is not by cycles (the paper's DTW aligns whole takes).
TakeCycles cycles_to_register(const PreparedTakes& p, const PreparedTake& t, const AlignmentOptions& align) {
  if (align.method != DtwMethod::kSlope || align.time_base != TimeBase::kCycles) return {};
  const TakeCycles& reference = p.takes.front().cycles;
  if (reference.kind != CycleKind::kGait || t.cycles.kind != CycleKind::kGait || t.cycles.foot == reference.foot)
    return t.cycles;
  CycleOptions at_foot;
  at_foot.foot = reference.foot;
  GaitJoints joints;
  const Eigen::MatrixXd legs = feet_signals(t.canonical.local, p.feet, &joints);
  TakeCycles at = cycles_from_feet(t.own_contacts, legs, joints, p.feet, at_foot,
                                   [&]() -> const Eigen::MatrixXd& { return t.canonical.local; });
  if (at.kind == CycleKind::kGait && !at.cycles.empty()) return at;
  return cycles_from_other_foot(t.cycles, t.own_contacts, reference.foot, static_cast<int>(t.world.rows()));
}

// Whether every cycle ends before the take's last frame, as register_by_cycles reads them (a
// loop's cycle [0, F), whose end is the first frame again, is aligned whole instead).
bool ends_inside(const TakeCycles& cycles, Eigen::Index frames) {
  for (const Cycle& c : cycles.cycles)
    if (c.end >= frames) return false;
  return true;
}

// Why two takes asked to be registered by cycles were aligned whole (empty when cycles were not
// asked for): which take has no cycles, or none of the kind the other's are, and why.
std::string why_whole(const TakeCycles& reference, const TakeCycles& take, const AlignmentOptions& align,
                      const std::string& reference_name, const std::string& take_name) {
  if (align.method != DtwMethod::kSlope || align.time_base != TimeBase::kCycles) return "";
  auto none = [](const std::string& name, const TakeCycles& c) {
    return name + " has no cycles" + (c.reason.empty() ? std::string() : ": " + c.reason);
  };
  if (reference.cycles.empty()) return none(reference_name, reference);
  if (take.cycles.empty()) return none(take_name, take);
  if (reference.kind != take.kind)
    return reference_name + "'s cycles are " + cycle_kind_name(reference.kind) + ", " + take_name + "'s " +
           cycle_kind_name(take.kind) + (take.reason.empty() ? std::string() : " (" + take.reason + ")");
  return "";
}

// A loop reference whose first frame would follow its last gets that frame appended (its first
// pose, one step on from its last), so its one cycle ends inside its frames as a cycle must, and
// the mix reaches the end of the loop. The take's world, canonical motion, contacts and cycles are
// made again with it.
void append_closing_frame(PreparedTake& t, const PreparedTakes& p, const int leg[6]) {
  const Eigen::Index frames = t.world.rows();
  if (frames < 3) return;
  Eigen::MatrixXd steps = Eigen::MatrixXd::Zero(2, 3);
  steps.row(0) = root_steps(t.canonical).row(frames - 2);
  Eigen::MatrixXd ground;
  Eigen::VectorXd heading;
  integrate_root(steps, t.canonical.ground.row(frames - 1).transpose(), t.canonical.heading[frames - 1], &ground,
                 &heading);
  Eigen::MatrixXd closing;
  to_world(t.canonical.local.topRows(1), ground.bottomRows(1), heading.tail(1), &closing);
  t.world.conservativeResize(frames + 1, Eigen::NoChange);
  t.world.row(frames) = closing.row(0);
  t.canonical = to_canonical(t.world, 0, leg[0], leg[3]);
  t.own_local_t = t.canonical.local.transpose();
  contacts_and_cycles(t.world, t.canonical, p.feet, p.majors, &t.own_contacts, &t.cycles);
}

// How many times a loop take is repeated to be registered: enough for one cycle window moved to
// any phase, with the fades' frames running on before and after it.
int loop_repeats(int loop_frames, int fade) { return 4 + 2 * ((fade + loop_frames - 1) / loop_frames); }

// F x 2 kFootJoints: PreparedTake::foot_travel of world (F x 3M) with heading (F).
Eigen::MatrixXd foot_travel(const Eigen::MatrixXd& world, const Eigen::VectorXd& heading, const FootRig& feet) {
  const Eigen::Index frames = world.rows();
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(frames, 2 * kFootJoints);
  Eigen::MatrixXd planted;
  std::vector<double> heights;
  planted_frames(world, feet, planted, heights, nullptr, kTravelBandScale);
  const std::array<int, kFootJoints> columns = foot_joint_columns(feet);
  for (Eigen::Index f = 0; f + 1 < frames; ++f) {
    const double c = std::cos(heading[f]), s = std::sin(heading[f]);
    for (int j = 0; j < kFootJoints; ++j) {
      const int col = columns[static_cast<size_t>(j)];
      double bx = 0.0, bz = 0.0;
      if (col >= 0 && planted(f, j) > 0.5 && planted(f + 1, j) > 0.5) {
        const double dx = world(f + 1, 3 * col) - world(f, 3 * col);
        const double dz = world(f + 1, 3 * col + 2) - world(f, 3 * col + 2);
        bx = c * dx - s * dz;
        bz = s * dx + c * dz;
      }
      out(f + 1, 2 * j) = out(f, 2 * j) + bx;
      out(f + 1, 2 * j + 1) = out(f, 2 * j + 1) + bz;
    }
  }
  return out;
}

// F x kFootJoints: PreparedTake::foot_height of world (F x 3M).
Eigen::MatrixXd foot_height(const Eigen::MatrixXd& world, const FootRig& feet) {
  const std::array<int, kFootJoints> columns = foot_joint_columns(feet);
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(world.rows(), kFootJoints);
  for (int j = 0; j < kFootJoints; ++j) {
    const int c = columns[static_cast<size_t>(j)];
    if (c >= 0) out.col(j) = world.col(3 * c + 1);
  }
  return out;
}

}  // namespace

void PrepareOptions::Validate() const {
  if (!(fps >= 0) || fps > kMaxFps || !std::isfinite(fps))
    throw InputError("expected a frame rate from 1 to 1000 (or 0 to keep A's), found " + std::to_string(fps));
  align.Validate();
  foot_contacts.Validate();
}

namespace {

// The left and right legs' hip, knee and ankle columns.
using LegColumns6 = int[6];

// The takes' major joints mapped (the first two with the options' mappings when given), the
// joints they share (p.majors, p.parents), the working rate and the joints the alignment reads.
std::vector<MajorMapping> map_takes(const std::vector<std::shared_ptr<const Clip>>& clips,
                                    const PrepareOptions& options, PreparedTakes& p, LegColumns6& leg) {
  const int n = static_cast<int>(clips.size());
  std::vector<MajorMapping> mappings;
  for (int i = 0; i < n; ++i) {
    const MappingOverrides& given = i == 0 ? options.mapping_a : options.mapping_b;
    const bool overridden = i <= 1 && !given.entries.empty();
    mappings.push_back(map_major_joints(*clips[i], overridden ? &given : nullptr));
  }
  p.majors = shared_majors(clips, mappings, options.only_majors);
  p.parents = subset_parents(p.majors);
  p.fps = options.fps > 0 ? options.fps : clips[0]->fps();
  auto column = [&](MajorJoint j) { return major_column(p.majors, static_cast<int>(j)); };
  const MajorJoint legs[6] = {MajorJoint::kLeftHip,  MajorJoint::kLeftKnee,  MajorJoint::kLeftAnkle,
                              MajorJoint::kRightHip, MajorJoint::kRightKnee, MajorJoint::kRightAnkle};
  for (int k = 0; k < 6; ++k) leg[k] = column(legs[k]);
  p.feature_joints.left_ankle = leg[2];
  p.feature_joints.right_ankle = leg[5];
  p.feature_joints.left_wrist = column(MajorJoint::kLeftWrist);
  p.feature_joints.right_wrist = column(MajorJoint::kRightWrist);
  return mappings;
}

// A take's cycles at its own rate, with its joints as `mapping` finds them: FK of the hips and
// legs, their bones, the feet, the canonical frame, contacts and cycles (contacts_and_cycles
// reads the same columns of the whole pose); the rest of the body only for a take whose feet
// give no gait.
TakeCycles own_rate_cycles(const std::shared_ptr<const Clip>& clip, const MajorMapping& mapping) {
  const std::vector<int> majors = shared_major_joints(mapping, clip->source, mapping, clip->source);
  auto cycles_of = [&](const std::vector<int>& joints) {
    const MajorTake major = extract_major_take(*clip, mapping, joints, 0.0);
    const FootRig feet = make_foot_rig(joints, bone_lengths(major.world, subset_parents(joints)), major.fps);
    const CanonicalMotion canonical = to_canonical(major.world, 0, feet.legs[0].hip, feet.legs[1].hip);
    Eigen::MatrixXd contacts;
    TakeCycles cycles;
    contacts_and_cycles(major.world, canonical, feet, joints, &contacts, &cycles);
    return cycles;
  };
  std::vector<int> legs;
  for (int m : majors) {
    const auto j = static_cast<MajorJoint>(m);
    if (j == MajorJoint::kHips || (j >= MajorJoint::kLeftHip && j <= MajorJoint::kLeftToe) ||
        (j >= MajorJoint::kRightHip && j <= MajorJoint::kRightToe))
      legs.push_back(m);
  }
  if (legs.size() < majors.size()) {
    TakeCycles cycles = cycles_of(legs);
    if (cycles.kind == CycleKind::kGait) return cycles;
  }
  return cycles_of(majors);
}

// A file's rate this little (relatively) above the working rate is the working rate.
constexpr double kRateEpsilon = 1e-9;

// A take with no gait cycles at the working rate that has them at its own, higher rate gets its
// own cycles, carried to the working rate (frame f of the file at f x fps / its rate, rounded,
// within the take's frames): a strike in the last hundredths of a second of a short clip can
// fall after the working rate's last frame, and without it the clip would have no cycles and be
// aligned whole. A loop is left as the working rate finds it (its length must be whole frames
// there). frames: the take's frames at the working rate.
// Test: "cycles: the wild's short clips keep their cycles at the working rates 24 and 30 fps" (tests/engine/align/cycles_test.cpp).
void carry_own_rate_cycles(const std::shared_ptr<const Clip>& clip, const MajorMapping& mapping, double fps,
                           Eigen::Index frames, TakeCycles& cycles) {
  if (cycles.kind == CycleKind::kGait || cycles.loops() || !(clip->fps() > fps * (1.0 + kRateEpsilon))) return;
  const TakeCycles own = own_rate_cycles(clip, mapping);
  if (own.kind != CycleKind::kGait || own.loops() || own.cycles.empty()) return;
  const double scale = fps / clip->fps();
  TakeCycles carried = own;
  carried.cycles.clear();
  for (const Cycle& c : own.cycles) {
    const Cycle at{static_cast<int>(std::lround(c.begin * scale)),
                   static_cast<int>(std::min<long>(std::lround(c.end * scale), static_cast<long>(frames) - 1))};
    if (at.frames() >= 2 && (carried.cycles.empty() || carried.cycles.back().end <= at.begin)) carried.cycles.push_back(at);
  }
  if (carried.cycles.empty()) return;
  carried.period = own.period * scale;
  cycles = carried;
}

// Take i on its own timeline, in the reference's bones (the reference, i = 0, sets them, and
// the foot rig): world, canonical poses, contacts, cycles, planted feet and fastest joint.
void prepare_own_take(int i, const std::shared_ptr<const Clip>& clip, const MajorMapping& mapping,
                      const PrepareOptions& options, const LegColumns6& leg, PreparedTakes& p, JobControl* control) {
  PreparedTake& t = p.takes[static_cast<size_t>(i)];
  const double fps = p.fps;
  t.clip = clip;
  t.mapping = mapping;
  MajorTake major = extract_major_take(*t.clip, t.mapping, p.majors, fps);
  check_cancel(control);
  t.names = std::move(major.names);
  if (i == 0) {
    t.world = std::move(major.world);
    p.lengths = bone_lengths(t.world, p.parents);
    // The reference in its own mean bone lengths, as every output is (paper 3.7): a rig whose
    // bones stretch (a glTF thigh scaled over a run) or whose major chains skip a joint is
    // measured (planted feet, their moves) as its outputs will be, so strength 0 gives it back.
    apply_limb_lengths(t.world, p.parents, p.lengths);
    p.feet = make_foot_rig(p.majors, p.lengths, fps, options.foot_contacts);
  } else {
    const std::vector<double> own_lengths = bone_lengths(major.world, p.parents);
    t.world = retarget_positions(major.world, p.parents, p.lengths, leg_length(p.lengths, leg),
                                 leg_length(own_lengths, leg));
    adopt_group_shapes(t.world, p.takes.front().world, p.parents);
    apply_limb_lengths(t.world, p.parents, p.lengths);
  }
  t.canonical = to_canonical(t.world, 0, leg[0], leg[3]);
  t.own_local_t = t.canonical.local.transpose();
  contacts_and_cycles(t.world, t.canonical, p.feet, p.majors, &t.own_contacts, &t.cycles);
  carry_own_rate_cycles(t.clip, t.mapping, fps, t.world.rows(), t.cycles);
  // A loop clip whose last frame shows its first again is measured without it, as its outputs
  // (cut to the loop, closed at the seam) are.
  const bool closing_last = t.cycles.loops() && t.cycles.loop_frames == t.world.rows() - 1;
  t.planted = closing_last ? planted_speed(Eigen::MatrixXd(t.world.topRows(t.cycles.loop_frames)), p.feet)
                           : planted_speed(t.world, p.feet);
  t.fastest_joint = fastest_joint_speed(t.world, fps);
  if (i == 0 && t.cycles.loops() && t.cycles.loop_frames == t.world.rows()) append_closing_frame(t, p, leg);
}

// Takes that neither walk are aligned by their structure (rest, action, rest: align_by_structure)
// on the default method and time base, unless one is a loop clip that the other's cycles
// register with (its cycle read across its end) or both repeat without a rest (registered stroke
// by stroke, by cycles). A loop whose other take has no cycles to match (a gesture held against a
// looping one) is aligned by structure too: whole DTW would leave out what it cannot match.
bool aligns_by_structure(const TakeCycles& reference, const TakeCycles& take, const AlignmentOptions& o) {
  if (o.method != DtwMethod::kSlope || o.time_base != TimeBase::kCycles) return false;
  if (reference.kind == CycleKind::kGait || take.kind == CycleKind::kGait) return false;
  if ((reference.loops() || take.loops()) && cycles_register(reference, take)) return false;
  const bool rests = reference.spans.rest_before + reference.spans.rest_after + take.spans.rest_before +
                         take.spans.rest_after > 0 || reference.spans.still() || take.spans.still();
  return rests || !cycles_register(reference, take);
}

// Whether a take gives the reference its posture only, by the default method and time base: one of
// the two walks (gait cycles) and the other does not, so that they share no part to match (a walk
// and a wave, a bow, a kick or standing).
bool gives_posture_only(const TakeCycles& reference, const TakeCycles& take, const AlignmentOptions& o) {
  if (o.method != DtwMethod::kSlope || o.time_base != TimeBase::kCycles) return false;
  return (reference.kind == CycleKind::kGait) != (take.kind == CycleKind::kGait);
}

// The joints (M) neither the root nor in a leg (a leg's hip, given by leg, and every joint below
// it): the ones a posture's spread sizes.
std::vector<bool> above_the_legs(const std::vector<int>& parents, const LegColumns6& leg) {
  std::vector<bool> out(parents.size(), false);
  for (size_t j = 0; j < parents.size(); ++j) {
    bool in_leg = false;
    for (int a = static_cast<int>(j); a >= 0 && !in_leg; a = parents[static_cast<size_t>(a)])
      in_leg = a == leg[0] || a == leg[3];
    out[j] = parents[j] >= 0 && !in_leg;
  }
  return out;
}

// A structure note with the takes' names for "A" and "B" where they are not a pair's.
std::string named_note(const std::string& note, const std::string& a, const std::string& b) {
  if (a == "A" && b == "B") return note;
  std::string out;
  for (size_t k = 0; k < note.size(); ++k) {
    const bool word = (k == 0 || note[k - 1] == ' ' || note[k - 1] == '(') &&
                      (k + 1 == note.size() || note[k + 1] == ' ' || note[k + 1] == '\'');
    if (word && note[k] == 'A') out += a;
    else if (word && note[k] == 'B') out += b;
    else out += note[k];
  }
  return out;
}

// The reference as its file has it, where its own timeline is extended with replays of its
// cycles (extend_reference): takes that are not registered by cycles (a stance, a gesture, a
// whole-take match) are aligned onto these frames, and their warps then laid on the extended
// ones, holding where the replays are (extended_warp), so that a mix that leaves the replays
// out (at the reference's weight 1, a transfer) plays them as aligned on the reference itself.
struct OwnReference {
  CanonicalMotion canonical;  // the file's frames; empty when the reference is not extended
  int resume = 0, extra = 0;  // the file's frame after which the replays come, and their frames
  bool extended() const { return extra > 0; }
};

// An alignment onto the reference's file frames laid on its extended frames: a frame f of the
// reference from `resume` on becomes f + extra, and over the replays the take holds the frame
// it has at `resume` (a sample there and one at resume + extra, the take's frame the same).
void extended_warp(const OwnReference& own, Alignment& al) {
  if (!own.extended()) return;
  const double r = own.resume, e = own.extra;
  auto moved = [&](double f) { return f >= r ? f + e : f; };
  const TimeWarp& w = al.warp;
  const int u = w.samples();
  int at = 0;  // the first sample at or past resume
  while (at < u && w.a[at] < r) ++at;
  std::vector<double> a, b, c, sl;
  auto push = [&](double fa, double fb, int from, double sv) {
    a.push_back(fa);
    b.push_back(fb);
    c.push_back(al.cost_ratio.size() > from ? al.cost_ratio[from] : 0.0);
    sl.push_back(sv);
  };
  int inserted = 0;
  for (int k = 0; k < u; ++k) {
    if (k == at && at > 0 && at < u) {
      // The take's frame at resume, held over the replays.
      const double t = (r - w.a[at - 1]) / std::max(1e-12, w.a[at] - w.a[at - 1]);
      const double fb = w.a[at] == r ? w.b[at] : w.b[at - 1] + t * (w.b[at] - w.b[at - 1]);
      push(r, fb, at, 0.0);
      ++inserted;
      if (w.a[at] > r) {
        push(r + e, fb, at, 0.0);
        ++inserted;
      }
    }
    push(moved(w.a[k]), w.b[k], k, al.slope.size() > k ? al.slope[k] : 0.0);
  }
  const int n = static_cast<int>(a.size());
  al.warp.a = Eigen::Map<Eigen::VectorXd>(a.data(), n);
  al.warp.b = Eigen::Map<Eigen::VectorXd>(b.data(), n);
  al.cost_ratio = Eigen::Map<Eigen::VectorXd>(c.data(), n);
  al.slope = Eigen::Map<Eigen::VectorXd>(sl.data(), n);
  for (auto& [i, j] : al.path) i = static_cast<int>(moved(i));
  al.a_first = static_cast<int>(moved(al.a_first));
  al.a_last = static_cast<int>(moved(al.a_last));
  al.frames_a += own.extra;
  for (auto& [first, last] : al.poor) {
    if (first >= at) first += inserted;
    if (last >= at) last += inserted;
  }
}

// Take i (> 0) aligned onto the reference: by cycles where both repeat (its own timeline then
// becomes the registered take, its cycles on the reference's), else whole; with the alignment's
// warnings.
void align_onto_reference(int i, const PrepareOptions& options, const LegColumns6& leg, const OwnReference& own_reference,
                          PreparedTakes& p, JobControl* control) {
  const int n = p.size();
  const double fps = p.fps;
  const PreparedTake& reference = p.takes.front();
  const TakeCycles& slots = reference.timeline_cycles();
  const CanonicalMotion& file_frames = own_reference.extended() ? own_reference.canonical : reference.canonical;
  PreparedTake& t = p.takes[static_cast<size_t>(i)];
  TakeCycles own = cycles_to_register(p, t, options.align);
  const int fade = std::max(2, static_cast<int>(std::lround(kPostureFadeCycles * reference.cycles.period)));
  // A loop take is read across its end (unrolled); a take's cycles begin at the phase of the
  // gait the reference's begin at (a loop reference's where the clip begins).
  const CanonicalMotion* take_motion = &t.canonical;
  const Eigen::MatrixXd* take_contacts = &t.own_contacts;
  UnrolledLoop unrolled;
  if (cycles_register(reference.cycles, own) && own.loops()) {
    const int repeats = loop_repeats(own.loop_frames, fade);
    unrolled = unroll_loop(t.canonical, t.own_contacts, own.loop_frames, repeats);
    const int middle = own.loop_frames * (repeats / 2);
    own.cycles = {{middle, middle + own.loop_frames}};
    take_motion = &unrolled.motion;
    take_contacts = &unrolled.contacts;
  }
  if (cycles_register(reference.cycles, own) && own.kind == CycleKind::kGait &&
      (own.strike_phase != 0.0 || reference.cycles.strike_phase != 0.0))
    own = cycles_at_phase(own, reference.cycles.strike_phase, static_cast<int>(take_motion->local.rows()));
  // The take registered (its timeline becomes the registered motion): aligned along it, and its
  // poses, faded or eased across a seam or moved by a posture, put back to the reference's bone
  // lengths, the canonical poses read again from them.
  auto adopt = [&](RegisteredMotion& registered) {
    t.alignment = align_by_cycles(reference.canonical, registered, p.feature_joints, p.feet.leg_length, fps,
                                  options.align, control);
    to_world(registered.motion.local, registered.motion.ground, registered.motion.heading, &t.world);
    apply_limb_lengths(t.world, p.parents, p.lengths);
    t.canonical = to_canonical(t.world, 0, leg[0], leg[3]);
    t.own_contacts = std::move(registered.contacts);
    t.registration = std::move(registered.registration);
    t.own_local_t = t.canonical.local.transpose();
  };
  if (cycles_register(slots, own) && ends_inside(slots, reference.canonical.local.rows()) &&
      ends_inside(own, take_motion->local.rows())) {
    RegisteredMotion registered = register_by_cycles(reference.canonical, reference.own_contacts, slots,
                                                     *take_motion, *take_contacts, own, fade);
    // An unrolled loop's frames are its file's frames modulo the loop.
    if (unrolled.loop_frames > 0)
      for (double& f : registered.registration.source)
        if (!std::isnan(f)) f = std::fmod(f, double(unrolled.loop_frames));
    adopt(registered);
  } else if (gives_posture_only(reference.cycles, own, options.align)) {
    // One of the two walks and the other does not (a walk on a standing or waving reference, a
    // wave, a bow or a kick on a walking one): no frame of the take matches, so it gives its
    // posture only, as between a reference's cycles (matching steps to a standing take by DTW
    // would slide the feet and shake the limbs, and leave out what it cannot match). Tests:
    // "posture registration: a walk's style put on a standing take moves only its posture"
    // (cycle_registration_test.cpp), "a take that does not walk gives a walking reference its
    // posture only" (alignment_pipeline_test.cpp).
    // A walk's arms swing with its steps, a size of movement its own locomotion sets; a take that
    // does not walk (an exhausted wave's small strokes, a masculine one's large) sizes the
    // reference's arms, spine and head with its own.
    const std::vector<bool> sized = own.kind == CycleKind::kGait ? std::vector<bool>(p.parents.size(), false)
                                                                 : above_the_legs(p.parents, leg);
    RegisteredMotion registered = register_posture_only(reference.canonical, reference.own_contacts,
                                                        take_posture(t.canonical.local, own), own, sized,
                                                        kPostureSpreadFloor * p.feet.leg_length);
    adopt(registered);
  } else if (aligns_by_structure(reference.cycles, own, options.align)) {
    t.alignment = align_by_structure(file_frames, reference.cycles.spans, t.canonical, t.cycles.spans,
                                     p.feature_joints, p.feet.leg_length, fps, options.align, control);
    extended_warp(own_reference, t.alignment);
  } else {
    t.alignment = align_takes(file_frames, t.canonical, p.feature_joints, p.feet.leg_length, fps,
                              options.align, control);
    // Registration by cycles was asked for (the default) but the takes cannot be registered (a
    // walk and a jump): where the open ends leave part of the reference out, all of both is
    // matched (closed ends), so that all of the reference plays at every weight; where their
    // lengths are too far apart for the slope limit, the open-ended alignment stays.
    const int frames = static_cast<int>(file_frames.local.rows());
    if (options.align.method == DtwMethod::kSlope && options.align.time_base == TimeBase::kCycles &&
        options.align.slope.open_ends && (t.alignment.a_first > 0 || t.alignment.a_last < frames - 1)) {
      AlignmentOptions closed = options.align;
      closed.slope.open_ends = false;
      try {
        t.alignment = align_takes(file_frames, t.canonical, p.feature_joints, p.feet.leg_length, fps, closed,
                                  control);
      } catch (const InputError&) {
        // Lengths beyond the slope limit: the open-ended alignment, with its warning.
      }
    }
    extended_warp(own_reference, t.alignment);
    t.alignment.whole_because = why_whole(reference.cycles, own, options.align, aligned_name(0, n, *reference.clip).name,
                                          aligned_name(i, n, *t.clip).name);
  }
  t.alignment.warnings = alignment_warnings(t.alignment, fps, aligned_name(0, n, *reference.clip),
                                            aligned_name(i, n, *t.clip));
  for (const std::string& note : t.alignment.notes) t.alignment.warnings.push_back(named_note(note, aligned_name(0, n, *reference.clip).name, aligned_name(i, n, *t.clip).name));
  // Whole-take alignment is the method for takes of which neither repeats (a bow, a wave once, a
  // kick): said only where one of them has cycles that could not be matched.
  const bool neither_repeats = reference.cycles.cycles.empty() && own.cycles.empty();
  if (!t.alignment.whole_because.empty() && !neither_repeats)
    t.alignment.warnings.push_back("aligned whole, not by cycles: " + t.alignment.whole_because);
  if (t.registration.posture_only())
    t.alignment.warnings.push_back("its posture only: " +
                                   why_whole(reference.cycles, own, options.align, aligned_name(0, n, *reference.clip).name,
                                             aligned_name(i, n, *t.clip).name) +
                                   "; " + aligned_name(i, n, *t.clip).name + " gives its " +
                                   (own.kind == CycleKind::kGait ? "mean pose over its cycles"
                                                                 : "mean pose and the size of its movements") +
                                   " throughout, none of its motion");
}

// The cycles take i (> 0) registers with when it has its own to lay on the reference's (not a
// loop, its cycles ending inside its frames), at the phase of the reference's; none otherwise.
TakeCycles cycles_to_fill(const PreparedTakes& p, const PreparedTake& t, const AlignmentOptions& align) {
  const TakeCycles& reference = p.takes.front().cycles;
  TakeCycles own = cycles_to_register(p, t, align);
  if (!cycles_register(reference, own) || own.loops()) return {};
  const int frames = static_cast<int>(t.canonical.local.rows());
  if (own.kind == CycleKind::kGait && (own.strike_phase != 0.0 || reference.strike_phase != 0.0))
    own = cycles_at_phase(own, reference.strike_phase, frames);
  return ends_inside(own, frames) ? own : TakeCycles();
}

// The reference's own timeline made long enough for every take's cycles: where a take to be
// registered by cycles has more than the reference (a walk of 7 strides blended with one of 5),
// the reference's last cycles are played again before its stop (extend_by_cycles), so that each
// take's every cycle has a slot and at its weight 1 the mix plays all of them. The reference's
// world, canonical motion and contacts become the extended ones, its registration says which of
// its frames each shows; a loop reference, which repeats without end, is left as it is.
OwnReference extend_reference(PreparedTakes& p, const PrepareOptions& options, const LegColumns6& leg) {
  PreparedTake& r = p.takes.front();
  const Eigen::Index frames = r.canonical.local.rows();
  OwnReference own;
  if (r.cycles.loops() || r.cycles.cycles.empty() || !ends_inside(r.cycles, frames)) return own;
  int slots = static_cast<int>(r.cycles.cycles.size());
  for (int i = 1; i < p.size(); ++i)
    slots = std::max(slots, static_cast<int>(cycles_to_fill(p, p.takes[static_cast<size_t>(i)], options.align).cycles.size()));
  if (slots <= static_cast<int>(r.cycles.cycles.size())) return own;
  RegisteredMotion extended = extend_by_cycles(r.canonical, r.own_contacts, r.cycles, slots);
  own.canonical = r.canonical;
  own.resume = r.cycles.cycles.back().end;
  own.extra = static_cast<int>(extended.motion.local.rows() - frames);
  to_world(extended.motion.local, extended.motion.ground, extended.motion.heading, &r.world);
  apply_limb_lengths(r.world, p.parents, p.lengths);
  r.canonical = to_canonical(r.world, 0, leg[0], leg[3]);
  r.own_local_t = r.canonical.local.transpose();
  r.own_contacts = std::move(extended.contacts);
  r.registration = std::move(extended.registration);
  return own;
}

// The slots (PreparedTakes::slots) on the common timeline: each of the reference's timeline
// cycles from the sample at its first frame to the sample at its end (whole reference frames are
// samples), and which takes call each their own.
void find_slots(PreparedTakes& p) {
  p.slots = CycleSlots();
  const PreparedTake& r = p.reference();
  bool any = false;
  for (int i = 1; i < p.size(); ++i) any |= !p.takes[static_cast<size_t>(i)].registration.pairs.empty();
  if (!any || r.cycles.loops()) return;
  const TakeCycles& cycles = r.timeline_cycles();
  const Eigen::VectorXd& at = r.frames;
  auto sample_at = [&](int frame) {
    const double* found = std::lower_bound(at.data(), at.data() + at.size(), double(frame) - 1e-9);
    return static_cast<int>(std::min<Eigen::Index>(found - at.data(), at.size() - 1));
  };
  const int n = p.size(), s_count = static_cast<int>(cycles.cycles.size());
  p.slots.own = Eigen::MatrixXd::Zero(s_count, n);
  for (int s = 0; s < s_count; ++s) {
    const Cycle& c = cycles.cycles[static_cast<size_t>(s)];
    p.slots.slots.push_back({sample_at(c.begin), sample_at(c.end)});
  }
  // A slot is a take's own where its cycle there is shown for the first time.
  auto own_of = [&](const PreparedTake& t, int i) {
    const std::vector<int>& pairs = t.registration.pairs;
    std::vector<bool> seen(t.registration.take_cycles.cycles.size() + 1, false);
    for (int s = 0; s < s_count; ++s) {
      const int c = s < static_cast<int>(pairs.size()) ? pairs[static_cast<size_t>(s)] : -1;
      const bool first = c >= 0 && c < static_cast<int>(seen.size()) && !seen[static_cast<size_t>(c)];
      if (c >= 0 && c < static_cast<int>(seen.size())) seen[static_cast<size_t>(c)] = true;
      p.slots.own(s, i) = t.registration.take_cycles.loops() || first ? 1.0 : 0.0;
    }
  };
  if (r.registration.pairs.empty()) p.slots.own.col(0).setOnes();
  else own_of(r, 0);
  for (int i = 1; i < n; ++i) {
    const PreparedTake& t = p.takes[static_cast<size_t>(i)];
    if (t.registration.pairs.empty()) p.slots.own.col(i) = p.slots.own.col(0);
    else own_of(t, i);
  }
}

// Every take on the common timeline (p.timeline set), placed where the reference stands when its
// match starts: poses, ground, steps and contacts per sample, and the whole turns that keep each
// take's facing within about half a turn of the reference's.
void place_on_timeline(PreparedTakes& p) {
  const PreparedTake& reference = p.takes.front();
  for (int i = 0; i < p.size(); ++i) {
    PreparedTake& t = p.takes[static_cast<size_t>(i)];
    PlacedRoot placed{t.canonical.ground, t.canonical.heading};
    if (i > 0) {
      const TimeWarp& warp = t.alignment.warp;
      placed = place_at(reference.canonical, warp.a[0], t.canonical, warp.b[0]);
    }
    to_world(t.canonical.local, placed.ground, placed.heading, &t.world_placed);
    t.frames = p.timeline.frames[static_cast<size_t>(i)];
    t.local = sample_rows(t.canonical.local, t.frames);
    t.ground = sample_rows(placed.ground, t.frames);
    const Eigen::VectorXd heading = sample_rows(placed.heading, t.frames);
    // A warp may skip frames from one sample to the next (the paper's); the root must not
    // teleport (root_path.h limit_warped_steps). Where no take skips, this changes nothing.
    t.steps = limit_warped_steps(root_steps(t.ground, heading), t.frames, kMaxWarpSpeedup);
    t.contacts = carry_contacts(t.own_contacts, t.frames);
  }
  p.reference_heading = sample_rows(reference.canonical.heading, reference.frames);
  // Kept apart: the synthesis spreads each over a moment so a mix in between turns smoothly
  // where it flips.
  for (PreparedTake& t : p.takes) t.turn_flips = match_turns(t.steps, reference.steps).col(2) - t.steps.col(2);
}

// Normalization: each take's own mean pose, one scale for all (per-channel scales would divide by
// zero on constant channels, the hips' x and z in the canonical frame).
void normalize_takes(PreparedTakes& p) {
  double sum = 0.0, count = 0.0;
  for (PreparedTake& t : p.takes) {
    t.mean = t.local.colwise().mean();
    sum += (t.local.rowwise() - t.mean).squaredNorm();
    count += static_cast<double>(t.local.size());
  }
  p.scale = count > 0 ? std::sqrt(sum / count) : 1.0;
  if (!(p.scale > 0) || !std::isfinite(p.scale)) p.scale = 1.0;
  for (PreparedTake& t : p.takes) t.x = (t.local.rowwise() - t.mean) / p.scale;
}

}  // namespace

std::shared_ptr<const PreparedTakes> prepare_takes(const std::vector<std::shared_ptr<const Clip>>& clips,
                                                   const PrepareOptions& options, JobControl* control,
                                                   StageTimes* times) {
  StageTimes own;
  StageTimes& spent = times != nullptr ? *times : own;
  const int n = static_cast<int>(clips.size());
  if (n < 2 || n > kMaxPaletteTakes)
    throw InputError("a palette takes from 2 to " + std::to_string(kMaxPaletteTakes) + " takes, found " +
                     std::to_string(n));
  options.Validate();
  const auto t0 = Clock::now();
  auto p = std::make_shared<PreparedTakes>();
  LegColumns6 leg;
  const std::vector<MajorMapping> mappings = map_takes(clips, options, *p, leg);
  report_progress(control, 0.1f);
  p->takes.resize(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i)
    prepare_own_take(i, clips[static_cast<size_t>(i)], mappings[static_cast<size_t>(i)], options, leg, *p, control);
  spent.preprocess_ms = ms_since(t0);
  report_progress(control, 0.3f);

  const auto t1 = Clock::now();
  const OwnReference own_reference = extend_reference(*p, options, leg);
  std::vector<const TimeWarp*> warps;
  for (int i = 1; i < n; ++i) {
    align_onto_reference(i, options, leg, own_reference, *p, control);
    warps.push_back(&p->takes[static_cast<size_t>(i)].alignment.warp);
  }
  spent.dtw_ms = ms_since(t1);
  report_progress(control, 0.8f);

  // Each take's planted foot joints' travel in its body's frame, on its own frames.
  // and how high each is.
  for (PreparedTake& t : p->takes) {
    t.foot_travel = foot_travel(t.world, t.canonical.heading, p->feet);
    t.foot_height = foot_height(t.world, p->feet);
  }
  const auto t2 = Clock::now();
  p->timeline = common_timeline(warps);
  place_on_timeline(*p);
  find_slots(*p);
  normalize_takes(*p);
  spent.preprocess_ms += ms_since(t2);
  check_cancel(control);
  report_progress(control, 1.0f);
  return p;
}

std::vector<int> export_joints(const PreparedTakes& prepared) {
  std::vector<int> joints;
  for (int major : prepared.majors) joints.push_back(prepared.reference().mapping.joint[major]);
  return joints;
}

TakeCycles take_cycles(const std::shared_ptr<const Clip>& clip) {
  // What prepare_takes does for the reference of a pair of the take with itself, at its own
  // rate, and nothing more (own_rate_cycles). The skeleton alone first (the motion is read only
  // where the rest pose shows no legs, a Z-up rig's: then as prepare_takes reads it, with its
  // motion).
  MajorMapping mapping = map_major_joints(clip->skeleton);
  if (!has_needed_joints(mapping)) mapping = map_major_joints(*clip);
  return own_rate_cycles(clip, mapping);
}

Eigen::VectorXd frames_in_take(const PreparedTake& take, const Eigen::VectorXd& frames) {
  if (take.registration.empty()) return frames;
  const Eigen::VectorXd& source = take.registration.source;
  const Eigen::Index last = source.size() - 1;
  Eigen::VectorXd out(frames.size());
  for (Eigen::Index k = 0; k < frames.size(); ++k) {
    const double at = std::clamp(frames[k], 0.0, double(last));
    const Eigen::Index r = std::min<Eigen::Index>(static_cast<Eigen::Index>(at), std::max<Eigen::Index>(last - 1, 0));
    const double f = at - double(r);
    const double s0 = source[r], s1 = source[std::min(r + 1, last)];
    // Between two frames of one run of the take's own frames, in between; else the nearer.
    out[k] = std::abs(s1 - s0) <= 1.0 + 1e-9 ? s0 + f * (s1 - s0) : (f < 0.5 ? s0 : s1);
  }
  return out;
}

Eigen::VectorXi cycles_shown(const PreparedTake& take, const Eigen::VectorXd& frames) {
  Eigen::VectorXi out(frames.size());
  const Eigen::Index last = take.registration.source_cycle.size() - 1;
  const std::vector<Cycle>& own = take.cycles.cycles;
  for (Eigen::Index k = 0; k < frames.size(); ++k) {
    if (!take.registration.empty()) {
      out[k] = take.registration.source_cycle[std::clamp<Eigen::Index>(std::lround(frames[k]), 0, last)];
      continue;
    }
    const auto at = std::upper_bound(own.begin(), own.end(), frames[k],
                                     [](double f, const Cycle& c) { return f < c.begin; });
    out[k] = at != own.begin() && frames[k] < std::prev(at)->end ? static_cast<int>(std::prev(at) - own.begin()) : -1;
  }
  return out;
}

}  // namespace mostyle
