#include "engine/align/cycle_registration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "engine/base/error.h"
#include "engine/kinematics/ease.h"
#include "engine/prepare/root_path.h"

namespace mostyle {

int replay_cycle(int k, int n, int slots) {
  if (k < n) return k;
  return ((k - slots) % n + n) % n;
}

std::vector<int> pair_cycles(const TakeCycles& reference, const TakeCycles& take) {
  std::vector<int> pairs;
  if (take.cycles.empty()) return pairs;
  const int n = static_cast<int>(take.cycles.size()), slots = static_cast<int>(reference.cycles.size());
  for (int k = 0; k < slots; ++k) pairs.push_back(replay_cycle(k, n, slots));
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
  const TakeCycles& reference_cycles;
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
  const bool eased = seam.squaredNorm() > 0.0;
  for (int j = 0; j < c.frames(); ++j, ++v) {
    const int f = c.begin + j;
    out.motion.local.row(v) = in.take.local.row(f) + (1.0 - double(j) / c.frames()) * seam;
    out.contacts.row(v) = in.take_contacts.row(f);
    steps.row(v) = in.take_steps.row(f);
    // A seam's first frame shows the pose the cycle before ended on.
    reg.source[v] = j == 0 && eased ? in.paired(reg, si - 1).end : f;
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

// Whether a take is under way at its first frame (start) or its last (stop): its root moves at
// least half its median speed over its cycles, averaged over a quarter of a cycle there; a take
// that starts from standing or stops is not. steps: root_steps (F x 3).
bool under_way(const Eigen::MatrixXd& steps, const TakeCycles& cycles, bool start) {
  const Eigen::Index frames = steps.rows();
  std::vector<double> speeds;
  for (const Cycle& c : cycles.cycles)
    for (int f = c.begin; f < c.end && f + 1 < frames; ++f) speeds.push_back(steps.row(f).head<2>().norm());
  if (speeds.empty() || frames < 2) return false;
  std::nth_element(speeds.begin(), speeds.begin() + speeds.size() / 2, speeds.end());
  const double median = speeds[speeds.size() / 2];
  const Eigen::Index k = std::clamp<Eigen::Index>(std::lround(cycles.period / 4), 1, frames - 1);
  // The last row of steps is zero (no step after the last frame): a stop is read before it.
  const Eigen::MatrixXd edge = start ? steps.topRows(k) : steps.middleRows(frames - 1 - k, k);
  return edge.leftCols(2).rowwise().norm().mean() >= 0.5 * median;
}

// The take's own frames before its first cycle or after its last, when span si is the
// reference's start or stop and is to show them: neither take is a loop (a loop has no start or
// stop of its own: the frames before its first cycle and after its last are one stretch of it),
// the take has such frames, and both takes are alike there (both start from standing,
// or both are already walking when they begin: a take cut in mid-walk). The reference's last
// cycle holds the take's last (pair_cycles), so its stop follows on. [t0, t1) frames of the
// take; empty when not.
constexpr double kEdgeLengthRatio = 1.5;
struct OwnEdge {
  int t0 = 0, t1 = 0;
  bool held = false;  // lengths beyond kEdgeLengthRatio: matched 1:1 next to the cycle, the rest a hold
  int frames() const { return t1 - t0; }
};

OwnEdge own_edge(const Registering& in, size_t si) {
  const Span& s = in.spans[si];
  if (s.cycle >= 0 || s.r1 <= s.r0 || in.take_cycles.kind != CycleKind::kGait || in.take_cycles.loops() ||
      in.reference_cycles.loops() || in.take_cycles.cycles.empty())
    return {};
  const int ft = static_cast<int>(in.take.local.rows());
  // Alike there. Lengths the cycles' own match allows (kEdgeLengthRatio) are matched as cycles
  // are; longer ones are held (edge_anchors), since a far longer stop squeezed onto a short one
  // would play at several times its speed on the reference's clock.
  auto fits = [&](OwnEdge& e, bool start) {
    const double n = s.r1 - s.r0, m = e.frames();
    e.held = m > kEdgeLengthRatio * n || n > kEdgeLengthRatio * m;
    return m > 0 && under_way(in.ref_steps, in.reference_cycles, start) == under_way(in.take_steps, in.take_cycles, start);
  };
  if (si == 0 && in.spans.size() > 1) {
    OwnEdge e{0, in.take_cycles.cycles.front().begin};
    if (fits(e, true)) return e;
  }
  if (si + 1 == in.spans.size() && si > 0) {
    OwnEdge e{in.take_cycles.cycles.back().end, ft};
    if (fits(e, false)) return e;
  }
  return {};
}

// The anchors of a start or stop laid with the take's own (own_edge) where their lengths are far
// apart: n reference frames, m of the take's from registered frame v. The frames next to the
// cycle are matched 1:1, min(n, m) of them; beyond, at the outer edge, the shorter of the two
// holds its first frame (a start) or its last (a stop) while the other plays on. The common
// timeline gives a hold the time its weights give the take that plays: at the take's weight 1
// its whole start or stop plays, in its timing, and none of the reference's excess; at 0 the
// reference's; on the reference's clock the take's excess is not played, nothing is squeezed.
void edge_anchors(const Span& s, bool start, int m, int v, std::vector<CycleRegistration::Anchor>& anchors) {
  const int n = s.r1 - s.r0;
  using Anchor = CycleRegistration::Anchor;
  if (start) {
    anchors.push_back(Anchor{s.r0, v, false, true});
    anchors.push_back(m > n ? Anchor{s.r0, v + m - n, false, false} : Anchor{s.r0 + n - m, v, false, false});
  } else {
    const int matched = std::min(n, m) - 1;
    anchors.push_back(Anchor{s.r0, v, false, false});
    anchors.push_back(Anchor{s.r0 + matched, v + matched, false, true});
  }
}

// Span si, the reference's start or stop, laid with the take's own start or stop (own_edge):
// its frames, in its timing, the registration's anchors matching the two spans as they match
// cycles. A stop that follows a reused cycle (the take has more cycles than the reference) meets
// it with the pose difference at the seam spread over the stop.
void copy_take_edge(const Registering& in, size_t si, const OwnEdge& edge, RegisteredMotion& out,
                    Eigen::MatrixXd& steps, Eigen::Index& v) {
  CycleRegistration& reg = out.registration;
  Eigen::RowVectorXd seam = Eigen::RowVectorXd::Zero(in.reference.local.cols());
  if (si > 0) {
    const Cycle& before = in.paired(reg, si - 1);
    if (before.end != edge.t0) seam = in.take.local.row(before.end) - in.take.local.row(edge.t0);
  }
  for (int f = edge.t0; f < edge.t1; ++f, ++v) {
    out.motion.local.row(v) = in.take.local.row(f) + (1.0 - double(f - edge.t0) / edge.frames()) * seam;
    out.contacts.row(v) = in.take_contacts.row(f);
    steps.row(v) = in.take_steps.row(f);
    reg.source[v] = f;
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
  const Registering in{reference,
                       reference_contacts,
                       take,
                       take_contacts,
                       take_cycles,
                       reference_cycles,
                       spans,
                       cycles_mean_pose(take.local, take_cycles) - cycles_mean_pose(reference.local, reference_cycles),
                       root_steps(reference),
                       root_steps(take),
                       fade};
  std::vector<OwnEdge> edges(spans.size());
  Eigen::Index v_frames = 0;
  for (size_t si = 0; si < spans.size(); ++si) {
    const Span& s = spans[si];
    edges[si] = own_edge(in, si);
    v_frames += s.cycle >= 0 ? take_cycles.cycles[static_cast<size_t>(reg.pairs[static_cast<size_t>(s.cycle)])].frames()
                : edges[si].frames() > 0 ? edges[si].frames()
                                         : s.r1 - s.r0;
  }
  out.motion.local.resize(v_frames, reference.local.cols());
  out.contacts.resize(v_frames, 2);
  Eigen::MatrixXd steps(v_frames, 3);
  reg.source = Eigen::VectorXd::Constant(v_frames, std::numeric_limits<double>::quiet_NaN());
  reg.source_cycle = Eigen::VectorXi::Constant(v_frames, -1);
  Eigen::Index v = 0;
  for (size_t si = 0; si < spans.size(); ++si) {
    const bool own = edges[si].frames() > 0;
    if (own && edges[si].held) edge_anchors(spans[si], si == 0, edges[si].frames(), static_cast<int>(v), reg.anchors);
    else reg.anchors.push_back({spans[si].r0, static_cast<int>(v), spans[si].cycle >= 0 || own});
    if (spans[si].cycle >= 0) copy_take_cycle(in, si, out, steps, v);
    else if (own) copy_take_edge(in, si, edges[si], out, steps, v);
    else fill_between_cycles(in, si, out, steps, v);
  }
  reg.anchors.push_back({static_cast<int>(fr) - 1, static_cast<int>(v_frames) - 1, false});
  integrate_root(steps, reference.ground.row(0).transpose(), reference.heading[0], &out.motion.ground,
                 &out.motion.heading);
  return out;
}

RegisteredMotion extend_by_cycles(const CanonicalMotion& motion, const Eigen::MatrixXd& contacts,
                                  const TakeCycles& cycles, int slots) {
  const Eigen::Index frames = motion.local.rows();
  const int n = static_cast<int>(cycles.cycles.size());
  if (contacts.rows() != frames) throw InputError("cycle extension: the take's poses and contacts do not have matching sizes");
  check_cycles(cycles, frames, "reference");
  if (n == 0 || slots <= n)
    throw InputError("cycle extension: expected more slots (" + std::to_string(slots) + ") than the take's " +
                     std::to_string(n) + " cycles");
  std::vector<int> shown;  // the cycle each slot shows
  for (int k = 0; k < slots; ++k) shown.push_back(replay_cycle(k, n, slots));
  const int resume = cycles.cycles.back().end;  // the stop, after the last own cycle
  Eigen::Index v_frames = frames;
  for (int k = n; k < slots; ++k) v_frames += cycles.cycles[static_cast<size_t>(shown[k])].frames();
  const Eigen::MatrixXd own_steps = root_steps(motion);
  RegisteredMotion out;
  CycleRegistration& reg = out.registration;
  reg.take_cycles = cycles;
  reg.pairs = shown;
  reg.cycles.kind = cycles.kind;
  reg.cycles.foot = cycles.foot;
  reg.cycles.period = cycles.period;
  reg.cycles.strike_phase = cycles.strike_phase;
  // The rests and actions in the extended frames: the replays lie inside the moving span.
  reg.cycles.spans = cycles.spans;
  ActionSpans& spans = reg.cycles.spans;
  const int extra = static_cast<int>(v_frames - frames);
  if (spans.frames > 0) {
    spans.frames += extra;
    for (FrameSpan& a : spans.actions) {
      if (a.begin >= resume) a.begin += extra;
      if (a.end >= resume) a.end += extra;
    }
  }
  out.motion.local.resize(v_frames, motion.local.cols());
  out.contacts.resize(v_frames, 2);
  Eigen::MatrixXd steps(v_frames, 3);
  reg.source.resize(v_frames);
  reg.source_cycle = Eigen::VectorXi::Constant(v_frames, -1);
  Eigen::Index v = 0;
  auto copy = [&](int f, int cycle, const Eigen::RowVectorXd* seam, double share) {
    out.motion.local.row(v) = motion.local.row(f);
    if (seam != nullptr) out.motion.local.row(v) += share * *seam;
    out.contacts.row(v) = contacts.row(f);
    steps.row(v) = own_steps.row(f);
    reg.source[v] = f;
    reg.source_cycle[v] = cycle;
    ++v;
  };
  auto cycle_of = [&](int f) {
    for (int k = 0; k < n; ++k)
      if (f >= cycles.cycles[static_cast<size_t>(k)].begin && f < cycles.cycles[static_cast<size_t>(k)].end) return k;
    return -1;
  };
  for (int f = 0; f < resume; ++f) copy(f, cycle_of(f), nullptr, 0.0);
  for (int k = 0; k < n; ++k) reg.cycles.cycles.push_back(cycles.cycles[static_cast<size_t>(k)]);
  using Anchor = CycleRegistration::Anchor;
  reg.anchors.push_back(Anchor{0, 0, false, false});
  reg.anchors.push_back(Anchor{resume, resume, false, true});  // the file's frame held over the replays
  int before_end = resume;  // the take's frame the last slot ended on
  for (int k = n; k < slots; ++k) {
    const Cycle& c = cycles.cycles[static_cast<size_t>(shown[k])];
    const Eigen::RowVectorXd seam = motion.local.row(before_end) - motion.local.row(c.begin);
    reg.cycles.cycles.push_back({static_cast<int>(v), static_cast<int>(v) + c.frames()});
    for (int j = 0; j < c.frames(); ++j) copy(c.begin + j, shown[k], &seam, 1.0 - double(j) / c.frames());
    reg.source[v - c.frames()] = before_end;  // its first frame shows the pose the slot before ended on
    before_end = c.end;
  }
  reg.anchors.push_back(Anchor{resume, static_cast<int>(v), false, false});
  for (int f = resume; f < frames; ++f) copy(f, cycle_of(f), nullptr, 0.0);
  reg.anchors.push_back(Anchor{static_cast<int>(frames) - 1, static_cast<int>(v_frames) - 1, false, false});
  integrate_root(steps, motion.ground.row(0).transpose(), motion.heading[0], &out.motion.ground, &out.motion.heading);
  return out;
}

TakePosture take_posture(const Eigen::MatrixXd& local, const TakeCycles& cycles) {
  const Eigen::Index rows = local.rows(), cols = local.cols();
  std::vector<Eigen::Index> frames;
  if (cycles.kind == CycleKind::kGait && !cycles.cycles.empty()) {
    for (const Cycle& c : cycles.cycles)
      for (Eigen::Index f = c.begin; f < c.end; ++f)
        frames.push_back(f < rows ? f : cycles.loops() ? f % cycles.loop_frames : rows - 1);
  } else {
    for (Eigen::Index f = 0; f < rows; ++f) frames.push_back(f);
  }
  TakePosture out;
  out.mean = Eigen::RowVectorXd::Zero(cols);
  out.spread = Eigen::RowVectorXd::Zero(cols / 3);
  if (frames.empty()) return out;
  for (Eigen::Index f : frames) out.mean += local.row(f);
  out.mean /= static_cast<double>(frames.size());
  for (Eigen::Index f : frames)
    for (Eigen::Index j = 0; j < cols / 3; ++j)
      out.spread[j] += (local.row(f).segment<3>(3 * j) - out.mean.segment<3>(3 * j)).squaredNorm();
  out.spread = (out.spread / static_cast<double>(frames.size())).cwiseSqrt();
  out.fastest = Eigen::RowVectorXd::Zero(cols / 3);
  for (Eigen::Index f = 1; f < rows; ++f)
    for (Eigen::Index j = 0; j < cols / 3; ++j)
      out.fastest[j] = std::max(out.fastest[j], (local.row(f).segment<3>(3 * j) - local.row(f - 1).segment<3>(3 * j)).norm());
  return out;
}

RegisteredMotion register_posture_only(const CanonicalMotion& reference, const Eigen::MatrixXd& reference_contacts,
                                       const TakePosture& take, const TakeCycles& take_cycles,
                                       const std::vector<bool>& sized, double spread_floor) {
  const Eigen::Index fr = reference.local.rows(), joints = reference.local.cols() / 3;
  if (fr < 1 || take.mean.size() != reference.local.cols() || take.spread.size() != joints || take.fastest.size() != joints ||
      static_cast<Eigen::Index>(sized.size()) != joints || reference_contacts.rows() != fr)
    throw InputError("posture registration: the takes' poses and contacts do not have matching sizes");
  if (!(spread_floor > 0.0)) throw InputError("posture registration: expected a spread floor above 0");
  const TakePosture own = take_posture(reference.local, TakeCycles());
  RegisteredMotion out;
  out.motion.local = reference.local;
  for (Eigen::Index j = 0; j < joints; ++j) {
    double scale = 1.0;
    if (sized[static_cast<size_t>(j)]) {
      scale = take.spread[j] / std::max(own.spread[j], spread_floor);
      if (own.fastest[j] > 0.0) scale = std::min(scale, std::max(1.0, take.fastest[j] / own.fastest[j]));
    }
    for (Eigen::Index c = 3 * j; c < 3 * j + 3; ++c)
      out.motion.local.col(c) = ((reference.local.col(c).array() - own.mean[c]) * scale + take.mean[c]).matrix();
  }
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
