#include "engine/align/cycle_registration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "engine/base/error.h"
#include "engine/kinematics/ease.h"

namespace mostyle {

std::vector<int> pair_cycles(const TakeCycles& reference, const TakeCycles& take) {
  std::vector<int> pairs;
  if (take.cycles.empty()) return pairs;
  const int n = static_cast<int>(take.cycles.size());
  for (size_t k = 0; k < reference.cycles.size(); ++k) pairs.push_back(static_cast<int>(k) % n);
  return pairs;
}

namespace {

// The mean pose (a row) over a take's cycle frames.
Eigen::RowVectorXd cycle_mean(const Eigen::MatrixXd& local, const TakeCycles& cycles) {
  Eigen::RowVectorXd sum = Eigen::RowVectorXd::Zero(local.cols());
  double n = 0.0;
  for (const Cycle& c : cycles.cycles) {
    sum += local.middleRows(c.begin, c.frames()).colwise().sum();
    n += c.frames();
  }
  return n > 0 ? Eigen::RowVectorXd(sum / n) : sum;
}

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

  // The spans, in order: between cycles (possibly empty) and each reference cycle.
  struct Span {
    int r0, r1;     // reference frames [r0, r1)
    int cycle;      // reference cycle index, -1 between cycles
  };
  std::vector<Span> spans;
  int r = 0;
  for (size_t k = 0; k < reference_cycles.cycles.size(); ++k) {
    const Cycle& c = reference_cycles.cycles[k];
    if (c.begin > r) spans.push_back({r, c.begin, -1});
    spans.push_back({c.begin, c.end, static_cast<int>(k)});
    r = c.end;
  }
  spans.push_back({r, static_cast<int>(fr), -1});  // fr > the last cycle's end (check_cycles)
  Eigen::Index v_frames = 0;
  for (const Span& s : spans)
    v_frames += s.cycle < 0 ? s.r1 - s.r0 : take_cycles.cycles[static_cast<size_t>(reg.pairs[static_cast<size_t>(s.cycle)])].frames();

  const Eigen::RowVectorXd offset = cycle_mean(take.local, take_cycles) - cycle_mean(reference.local, reference_cycles);
  const Eigen::MatrixXd ref_steps = root_steps(reference), take_steps = root_steps(take);
  const Eigen::Index channels = reference.local.cols();
  out.motion.local.resize(v_frames, channels);
  out.contacts.resize(v_frames, 2);
  Eigen::MatrixXd steps(v_frames, 3);
  reg.source = Eigen::VectorXd::Constant(v_frames, std::numeric_limits<double>::quiet_NaN());
  reg.source_cycle = Eigen::VectorXi::Constant(v_frames, -1);
  auto clamp_take = [&](int f) { return std::clamp<int>(f, 0, static_cast<int>(ft) - 1); };
  // A frame's step, the one before it at the take's last frame (whose step is zero: a take that
  // runs on past its end holds its pose, not its walk).
  auto moving = [&](int f) { return std::min<int>(f, std::max<int>(0, static_cast<int>(ft) - 2)); };

  Eigen::Index v = 0;
  for (size_t si = 0; si < spans.size(); ++si) {
    const Span& s = spans[si];
    reg.anchors.push_back({s.r0, static_cast<int>(v), s.cycle >= 0});
    if (s.cycle >= 0) {
      const int tc = reg.pairs[static_cast<size_t>(s.cycle)];
      const Cycle& c = take_cycles.cycles[static_cast<size_t>(tc)];
      // The seam with the cycle before, when it meets this one directly and the take did not go
      // on into this cycle there.
      Eigen::RowVectorXd seam = Eigen::RowVectorXd::Zero(channels);
      if (si > 0 && spans[si - 1].cycle >= 0) {
        const Cycle& before = take_cycles.cycles[static_cast<size_t>(reg.pairs[static_cast<size_t>(spans[si - 1].cycle)])];
        if (before.end != c.begin) seam = take.local.row(before.end) - take.local.row(c.begin);
      }
      reg.cycles.cycles.push_back({static_cast<int>(v), static_cast<int>(v) + c.frames()});
      for (int j = 0; j < c.frames(); ++j, ++v) {
        const int f = c.begin + j;
        out.motion.local.row(v) = take.local.row(f) + (1.0 - double(j) / c.frames()) * seam;
        out.contacts.row(v) = take_contacts.row(f);
        steps.row(v) = take_steps.row(f);
        reg.source[v] = f;
        reg.source_cycle[v] = tc;
      }
      continue;
    }
    // Between cycles: the reference moved by the take's posture, faded into the take's own
    // frames running on from the cycle before and into the cycle after.
    const int gap = s.r1 - s.r0;
    // Over `fade` frames from each cycle, however short the span: a span shorter than two fades
    // (a start before the first strike, a missed strike) is the take's own frames throughout,
    // crossed from the cycle before to the one after; the posture alone only further in.
    const int reach = std::max(1, fade);
    const Cycle* before = nullptr;
    const Cycle* after = nullptr;
    if (si > 0) before = &take_cycles.cycles[static_cast<size_t>(reg.pairs[static_cast<size_t>(spans[si - 1].cycle)])];
    if (si + 1 < spans.size())
      after = &take_cycles.cycles[static_cast<size_t>(reg.pairs[static_cast<size_t>(spans[si + 1].cycle)])];
    for (int g = s.r0; g < s.r1; ++g, ++v) {
      const int d1 = g - s.r0, d2 = s.r1 - 1 - g;  // frames from the cycle before, to the cycle after
      const double wa = before != nullptr ? 1.0 - smoothstep(double(d1) / reach) : 0.0;
      const double wb = after != nullptr ? 1.0 - smoothstep(double(d2) / reach) : 0.0;
      const double w = std::max(wa, wb);
      const double toward_after = before == nullptr ? 1.0 : after == nullptr ? 0.0 : gap == 1 ? 0.5 : smoothstep(double(d1) / (gap - 1));
      const int fa = before != nullptr ? clamp_take(before->end + d1) : 0;
      const int fb = after != nullptr ? clamp_take(after->begin - 1 - d2) : 0;
      Eigen::RowVectorXd pose = (1.0 - w) * (reference.local.row(g) + offset);
      Eigen::RowVector3d step = (1.0 - w) * ref_steps.row(g);
      if (w > 0.0) {
        pose += w * ((1.0 - toward_after) * take.local.row(fa) + toward_after * take.local.row(fb));
        step += w * ((1.0 - toward_after) * take_steps.row(moving(fa)) + toward_after * take_steps.row(moving(fb)));
      }
      out.motion.local.row(v) = pose;
      steps.row(v) = step;
      const int own = toward_after < 0.5 ? fa : fb;
      out.contacts.row(v) = w >= 0.5 ? Eigen::RowVector2d(take_contacts.row(own)) : Eigen::RowVector2d(reference_contacts.row(g));
      if (w >= 0.5) reg.source[v] = own;
    }
  }
  reg.anchors.push_back({static_cast<int>(fr) - 1, static_cast<int>(v_frames) - 1, false});
  integrate_root(steps, reference.ground.row(0).transpose(), reference.heading[0], &out.motion.ground,
                 &out.motion.heading);
  return out;
}

}  // namespace mostyle
