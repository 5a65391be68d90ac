#include "engine/align/cycle_registration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "engine/base/error.h"
#include "engine/kinematics/ease.h"
#include "engine/prepare/root_path.h"

namespace mostyle {

std::vector<int> pair_cycles(const TakeCycles& reference, const TakeCycles& take) {
  std::vector<int> pairs;
  if (take.cycles.empty()) return pairs;
  const int n = static_cast<int>(take.cycles.size());
  for (size_t k = 0; k < reference.cycles.size(); ++k) pairs.push_back(static_cast<int>(k) % n);
  return pairs;
}

namespace {

void check_cycles(const TakeCycles& cycles, Eigen::Index frames, const char* which) {
  int last_end = 0;
  for (size_t k = 0; k < cycles.cycles.size(); ++k) {
    const Cycle& c = cycles.cycles[k];
    if (c.begin < last_end || c.end <= c.begin || c.end >= frames)
      throw InputError(std::string("cycle registration: the ") + which + "'s cycle " + std::to_string(k + 1) +
                       " (frames " + std::to_string(c.begin) + " to " + std::to_string(c.end) +
                       ") does not fit its " + std::to_string(frames) + " frames in order");
    last_end = c.end;
  }
}

}  // namespace

bool cycles_register(const TakeCycles& reference, const TakeCycles& take) {
  if (reference.kind == CycleKind::kNone || reference.cycles.empty() || take.cycles.empty()) return false;
  if (reference.kind != take.kind) return false;
  return reference.kind != CycleKind::kGait || reference.foot == take.foot;
}

namespace {

// A stretch of the reference, in order: between cycles (possibly empty) or one of its cycles.
struct Span {
  int r0, r1;  // reference frames [r0, r1)
  int cycle;   // reference cycle index, -1 between cycles
};

// The reference's spans, from frame 0 to fr (fr > the last cycle's end: check_cycles).
std::vector<Span> reference_spans(const TakeCycles& reference_cycles, Eigen::Index fr) {
  std::vector<Span> spans;
  int r = 0;
  for (size_t k = 0; k < reference_cycles.cycles.size(); ++k) {
    const Cycle& c = reference_cycles.cycles[k];
    if (c.begin > r) spans.push_back({r, c.begin, -1});
    spans.push_back({c.begin, c.end, static_cast<int>(k)});
    r = c.end;
  }
  spans.push_back({r, static_cast<int>(fr), -1});
  return spans;
}

// What every span of the registration reads.
struct Registering {
  const CanonicalMotion& reference;
  const Eigen::MatrixXd& reference_contacts;
  const CanonicalMotion& take;
  const Eigen::MatrixXd& take_contacts;
  const TakeCycles& take_cycles;
  const std::vector<Span>& spans;
  Eigen::RowVectorXd offset;              // the take's mean posture less the reference's
  Eigen::MatrixXd ref_steps, take_steps;  // root_steps of each
  int fade;
  // The take's cycle paired with span si's reference cycle.
  const Cycle& paired(const CycleRegistration& reg, size_t si) const {
    return take_cycles.cycles[static_cast<size_t>(reg.pairs[static_cast<size_t>(spans[si].cycle)])];
  }
};

// Span si, a reference cycle: the paired take cycle's own frames from output frame v on (v
// advanced past them), its seam with the cycle before faded out over it where that cycle meets
// it directly and the take did not go on into this one there.
void copy_take_cycle(const Registering& in, size_t si, RegisteredMotion& out, Eigen::MatrixXd& steps, Eigen::Index& v) {
  CycleRegistration& reg = out.registration;
  const Eigen::Index channels = in.reference.local.cols();
  const int tc = reg.pairs[static_cast<size_t>(in.spans[si].cycle)];
  const Cycle& c = in.take_cycles.cycles[static_cast<size_t>(tc)];
  Eigen::RowVectorXd seam = Eigen::RowVectorXd::Zero(channels);
  if (si > 0 && in.spans[si - 1].cycle >= 0) {
    const Cycle& before = in.paired(reg, si - 1);
    if (before.end != c.begin) seam = in.take.local.row(before.end) - in.take.local.row(c.begin);
  }
  reg.cycles.cycles.push_back({static_cast<int>(v), static_cast<int>(v) + c.frames()});
  for (int j = 0; j < c.frames(); ++j, ++v) {
    const int f = c.begin + j;
    out.motion.local.row(v) = in.take.local.row(f) + (1.0 - double(j) / c.frames()) * seam;
    out.contacts.row(v) = in.take_contacts.row(f);
    steps.row(v) = in.take_steps.row(f);
    reg.source[v] = f;
    reg.source_cycle[v] = tc;
  }
}

// Span si, between cycles: the reference moved by the take's posture, faded into the take's own
// frames running on from the cycle before and into the cycle after, from output frame v on (v
// advanced past them).
void fill_between_cycles(const Registering& in, size_t si, RegisteredMotion& out, Eigen::MatrixXd& steps,
                         Eigen::Index& v) {
  CycleRegistration& reg = out.registration;
  const Span& s = in.spans[si];
  const int ft = static_cast<int>(in.take.local.rows());
  auto clamp_take = [&](int f) { return std::clamp<int>(f, 0, ft - 1); };
  // A frame's step, the one before it at the take's last frame (whose step is zero: a take that
  // runs on past its end holds its pose, not its walk).
  auto moving = [&](int f) { return std::min<int>(f, std::max<int>(0, ft - 2)); };
  const int gap = s.r1 - s.r0;
  // Over `fade` frames from each cycle, however short the span: a span shorter than two fades
  // (a start before the first strike, a missed strike) is the take's own frames throughout,
  // crossed from the cycle before to the one after; the posture alone only further in.
  const int reach = std::max(1, in.fade);
  const Cycle* before = si > 0 ? &in.paired(reg, si - 1) : nullptr;
  const Cycle* after = si + 1 < in.spans.size() ? &in.paired(reg, si + 1) : nullptr;
  for (int g = s.r0; g < s.r1; ++g, ++v) {
    const int d1 = g - s.r0, d2 = s.r1 - 1 - g;  // frames from the cycle before, to the cycle after
    const double wa = before != nullptr ? 1.0 - smoothstep(double(d1) / reach) : 0.0;
    const double wb = after != nullptr ? 1.0 - smoothstep(double(d2) / reach) : 0.0;
    const double w = std::max(wa, wb);
    const double toward_after = before == nullptr ? 1.0 : after == nullptr ? 0.0 : gap == 1 ? 0.5 : smoothstep(double(d1) / (gap - 1));
    const int fa = before != nullptr ? clamp_take(before->end + d1) : 0;
    const int fb = after != nullptr ? clamp_take(after->begin - 1 - d2) : 0;
    Eigen::RowVectorXd pose = (1.0 - w) * (in.reference.local.row(g) + in.offset);
    Eigen::RowVector3d step = (1.0 - w) * in.ref_steps.row(g);
    if (w > 0.0) {
      pose += w * ((1.0 - toward_after) * in.take.local.row(fa) + toward_after * in.take.local.row(fb));
      step += w * ((1.0 - toward_after) * in.take_steps.row(moving(fa)) + toward_after * in.take_steps.row(moving(fb)));
    }
    out.motion.local.row(v) = pose;
    steps.row(v) = step;
    const int own = toward_after < 0.5 ? fa : fb;
    out.contacts.row(v) =
        w >= 0.5 ? Eigen::RowVector2d(in.take_contacts.row(own)) : Eigen::RowVector2d(in.reference_contacts.row(g));
    if (w >= 0.5) reg.source[v] = own;
  }
}

}  // namespace

Eigen::RowVectorXd cycles_mean_pose(const Eigen::MatrixXd& local, const TakeCycles& cycles) {
  Eigen::RowVectorXd sum = Eigen::RowVectorXd::Zero(local.cols());
  double n = 0.0;
  const Eigen::Index rows = local.rows();
  for (const Cycle& c : cycles.cycles) {
    const Eigen::Index inside = std::clamp<Eigen::Index>(rows - c.begin, 0, c.frames());
    if (inside > 0) sum += local.middleRows(c.begin, inside).colwise().sum();
    for (Eigen::Index f = c.begin + inside; f < c.end; ++f)  // past the last frame
      sum += local.row(cycles.loops() ? f % cycles.loop_frames : rows - 1);
    n += c.frames();
  }
  return n > 0 ? Eigen::RowVectorXd(sum / n) : sum;
}

RegisteredMotion register_by_cycles(const CanonicalMotion& reference, const Eigen::MatrixXd& reference_contacts,
                                    const TakeCycles& reference_cycles, const CanonicalMotion& take,
                                    const Eigen::MatrixXd& take_contacts, const TakeCycles& take_cycles, int fade) {
  if (!cycles_register(reference_cycles, take_cycles))
    throw InputError("cycle registration: the takes' cycles are not of one kind, or begin at different feet");
  const Eigen::Index fr = reference.local.rows(), ft = take.local.rows();
  if (take.local.cols() != reference.local.cols() || reference_contacts.rows() != fr || take_contacts.rows() != ft)
    throw InputError("cycle registration: the takes' poses and contacts do not have matching sizes");
  check_cycles(reference_cycles, fr, "reference");
  check_cycles(take_cycles, ft, "take");
  RegisteredMotion out;
  CycleRegistration& reg = out.registration;
  reg.take_cycles = take_cycles;
  reg.pairs = pair_cycles(reference_cycles, take_cycles);
  reg.cycles.kind = take_cycles.kind;
  reg.cycles.foot = take_cycles.foot;
  reg.cycles.period = take_cycles.period;
  const std::vector<Span> spans = reference_spans(reference_cycles, fr);
  Eigen::Index v_frames = 0;
  for (const Span& s : spans)
    v_frames += s.cycle < 0 ? s.r1 - s.r0 : take_cycles.cycles[static_cast<size_t>(reg.pairs[static_cast<size_t>(s.cycle)])].frames();
  const Registering in{reference,
                       reference_contacts,
                       take,
                       take_contacts,
                       take_cycles,
                       spans,
                       cycles_mean_pose(take.local, take_cycles) - cycles_mean_pose(reference.local, reference_cycles),
                       root_steps(reference),
                       root_steps(take),
                       fade};
  out.motion.local.resize(v_frames, reference.local.cols());
  out.contacts.resize(v_frames, 2);
  Eigen::MatrixXd steps(v_frames, 3);
  reg.source = Eigen::VectorXd::Constant(v_frames, std::numeric_limits<double>::quiet_NaN());
  reg.source_cycle = Eigen::VectorXi::Constant(v_frames, -1);
  Eigen::Index v = 0;
  for (size_t si = 0; si < spans.size(); ++si) {
    reg.anchors.push_back({spans[si].r0, static_cast<int>(v), spans[si].cycle >= 0});
    if (spans[si].cycle >= 0) copy_take_cycle(in, si, out, steps, v);
    else fill_between_cycles(in, si, out, steps, v);
  }
  reg.anchors.push_back({static_cast<int>(fr) - 1, static_cast<int>(v_frames) - 1, false});
  integrate_root(steps, reference.ground.row(0).transpose(), reference.heading[0], &out.motion.ground,
                 &out.motion.heading);
  return out;
}

RegisteredMotion register_posture_only(const CanonicalMotion& reference, const Eigen::MatrixXd& reference_contacts,
                                       const CanonicalMotion& take, const TakeCycles& take_cycles) {
  const Eigen::Index fr = reference.local.rows(), ft = take.local.rows();
  if (fr < 1 || ft < 1 || take.local.cols() != reference.local.cols() || reference_contacts.rows() != fr)
    throw InputError("posture registration: the takes' poses and contacts do not have matching sizes");
  if (take_cycles.cycles.empty()) throw InputError("posture registration: the take has no cycles to give a posture");
  const Eigen::RowVectorXd posture = cycles_mean_pose(take.local, take_cycles) - reference.local.colwise().mean();
  RegisteredMotion out;
  out.motion.local = reference.local.rowwise() + posture;
  out.motion.ground = reference.ground;
  out.motion.heading = reference.heading;
  out.contacts = reference_contacts;
  CycleRegistration& reg = out.registration;
  reg.take_cycles = take_cycles;
  reg.source = Eigen::VectorXd::Constant(fr, std::numeric_limits<double>::quiet_NaN());
  reg.source_cycle = Eigen::VectorXi::Constant(fr, -1);
  reg.anchors = {{0, 0, false}, {static_cast<int>(fr) - 1, static_cast<int>(fr) - 1, false}};
  return out;
}

}  // namespace mostyle
