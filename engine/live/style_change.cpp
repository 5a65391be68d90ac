#include "engine/live/style_change.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/base/error.h"
#include "engine/kinematics/limb_length.h"
#include "engine/prepare/canonical_frame.h"
#include "engine/prepare/retarget.h"

namespace mostyle {
namespace {

constexpr int kMinPhases = 8;
constexpr int kMaxPhases = 4096;
// A phase is in a foot's stance when the foot is planted there in at least this share of the
// neutral's cycles.
constexpr double kStanceShare = 0.5;

// Throws when the takes cannot give a change by phase: the neutral walks in gait cycles, each
// style was registered onto them.
void check_takes(const PreparedTakes& p) {
  const PreparedTake& neutral = p.reference();
  if (neutral.cycles.kind != CycleKind::kGait || neutral.cycles.cycles.empty())
    throw InputError(neutral.clip->source + ": the neutral take has no gait cycles to lay a style on" +
                     (neutral.cycles.reason.empty() ? std::string() : " (" + neutral.cycles.reason + ")"));
  for (size_t i = 1; i < p.takes.size(); ++i) {
    const PreparedTake& t = p.takes[i];
    if (t.registration.empty())
      throw InputError(t.clip->source + ": the style take could not be laid on the neutral's gait cycles (" +
                       (t.alignment.whole_because.empty() ? std::string("its cycles do not match them")
                                                          : t.alignment.whole_because) +
                       ")");
  }
}

// A take's world positions (F x 3M, the neutral's bones) on the stream's: scaled by the legs,
// the stream's joint-group shapes and bone lengths (what prepare_takes does to a take that is
// not its reference), then in the canonical frame.
CanonicalMotion on_stream_bones(const Eigen::MatrixXd& world, const PreparedTakes& p, const Eigen::MatrixXd& rest,
                                const std::vector<double>& lengths, double leg_stream, double leg_neutral) {
  Eigen::MatrixXd w = retarget_positions(world, p.parents, lengths, leg_stream, leg_neutral);
  adopt_group_shapes(w, rest, p.parents);
  apply_limb_lengths(w, p.parents, lengths);
  return to_canonical(w, 0, p.feet.legs[0].hip, p.feet.legs[1].hip);
}

// Where the other foot first lands inside a cycle, as a share of it; -1 where it never does.
double other_strike(const Eigen::MatrixXd& contacts, const Cycle& c, int other) {
  for (int f = c.begin + 1; f < c.end; ++f)
    if (contacts(f, other) > 0.5 && contacts(f - 1, other) <= 0.5) return double(f - c.begin) / c.frames();
  return -1.0;
}

// Per cycle, where its other foot strikes (other_strike); in *mean, the mean over the cycles
// where it does (0.5 where it never does).
std::vector<double> other_strikes(const Eigen::MatrixXd& contacts, const std::vector<Cycle>& cycles, int other,
                                  double* mean) {
  std::vector<double> out;
  double sum = 0.0;
  int n = 0;
  for (const Cycle& c : cycles) {
    out.push_back(other_strike(contacts, c, other));
    if (out.back() >= 0.0) {
      sum += out.back();
      ++n;
    }
  }
  *mean = n > 0 ? sum / n : 0.5;
  return out;
}

// Phase `phase` of a cycle whose other foot strikes at `strike` (a share of it; outside (0, 1):
// unknown), phases matched by foot: the mean strike `mean` at the cycle's own, linear in time on
// either side of it.
double matched_phase(double phase, double mean, double strike) {
  if (strike <= 0.0 || strike >= 1.0) return phase;
  return phase < mean ? phase * strike / mean : strike + (phase - mean) * (1.0 - strike) / (1.0 - mean);
}

// (phases + 1) x cycles: the reference's frame (fractional) at phase k / phases of each of its
// cycles (k = 0 .. phases: the last row each cycle's end, the next one's start), phases matched
// by foot (strikes: one per cycle).
Eigen::MatrixXd phase_frames(const std::vector<Cycle>& cycles, const std::vector<double>& strikes, double mean,
                             int phases) {
  Eigen::MatrixXd out(phases + 1, static_cast<Eigen::Index>(cycles.size()));
  for (size_t i = 0; i < cycles.size(); ++i)
    for (int k = 0; k <= phases; ++k)
      out(k, static_cast<Eigen::Index>(i)) =
          cycles[i].begin + matched_phase(double(k) / phases, mean, strikes[i]) * cycles[i].frames();
  return out;
}

// A take's frames matching the reference's `frames`, through their common timeline (the
// reference's frame and the take's at each sample, both non-decreasing): linear between samples,
// held at the ends.
Eigen::MatrixXd matched_frames(const Eigen::MatrixXd& frames, const Eigen::VectorXd& reference,
                               const Eigen::VectorXd& take) {
  Eigen::MatrixXd out(frames.rows(), frames.cols());
  const Eigen::Index last = reference.size() - 1;
  for (Eigen::Index i = 0; i < frames.size(); ++i) {
    const double f = frames(i);
    const auto after = std::upper_bound(reference.data(), reference.data() + reference.size(), f);
    const Eigen::Index u = std::clamp<Eigen::Index>(after - reference.data() - 1, 0, std::max<Eigen::Index>(last - 1, 0));
    const Eigen::Index v = std::min(u + 1, last);
    const double span = reference[v] - reference[u];
    const double t = span > 0.0 ? std::clamp((f - reference[u]) / span, 0.0, 1.0) : 0.0;
    out(i) = take[u] + t * (take[v] - take[u]);
  }
  return out;
}

// (phases + 1) x 3M: local's pose at each row's frames (fractional, linear between frames),
// averaged over the columns.
Eigen::MatrixXd mean_poses(const Eigen::MatrixXd& local, const Eigen::MatrixXd& frames) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(frames.rows(), local.cols());
  const Eigen::Index last = local.rows() - 1;
  for (Eigen::Index k = 0; k < frames.rows(); ++k)
    for (Eigen::Index c = 0; c < frames.cols(); ++c) {
      const double at = std::clamp(frames(k, c), 0.0, double(last));
      const Eigen::Index r = std::min<Eigen::Index>(static_cast<Eigen::Index>(at), std::max<Eigen::Index>(last - 1, 0));
      const double f = std::clamp(at - double(r), 0.0, 1.0);
      out.row(k) += (1.0 - f) * local.row(r) + f * local.row(std::min(r + 1, last));
    }
  return out / static_cast<double>(frames.cols());
}

// A change by phase ((phases + 1) rows, the last the cycles' ends) made periodic: what the end
// and the start differ by spread evenly over the cycle (half taken off the end, half added to the
// start), the end row dropped, then smoothed by a [1 2 1] / 4 filter around the cycle.
PhaseTable periodic_table(const Eigen::MatrixXd& change) {
  const Eigen::Index phases = change.rows() - 1;
  const Eigen::RowVectorXd seam = change.row(phases) - change.row(0);
  PhaseTable raw(phases, change.cols());
  for (Eigen::Index k = 0; k < phases; ++k) raw.row(k) = change.row(k) - (double(k) / double(phases) - 0.5) * seam;
  PhaseTable out(phases, change.cols());
  for (Eigen::Index k = 0; k < phases; ++k)
    out.row(k) = 0.25 * raw.row((k + phases - 1) % phases) + 0.5 * raw.row(k) + 0.25 * raw.row((k + 1) % phases);
  return out;
}

// Per foot, the share of the cycles in which it is planted at each phase (contacts: F x 2),
// phases matched by foot as phase_means matches them.
std::array<Eigen::VectorXd, 2> stance_by_phase(const Eigen::MatrixXd& contacts, const std::vector<Cycle>& cycles,
                                               const std::vector<double>& strikes, double mean, int phases) {
  std::array<Eigen::VectorXd, 2> out{Eigen::VectorXd::Zero(phases), Eigen::VectorXd::Zero(phases)};
  const Eigen::Index last = contacts.rows() - 1;
  for (size_t i = 0; i < cycles.size(); ++i) {
    const Cycle& c = cycles[i];
    for (int k = 0; k < phases; ++k) {
      const double phase = matched_phase((k + 0.5) / phases, mean, strikes[i]);
      const Eigen::Index r = std::min<Eigen::Index>(std::lround(c.begin + phase * c.frames()), last);
      for (size_t side = 0; side < 2; ++side) out[side][k] += contacts(r, static_cast<Eigen::Index>(side)) > 0.5 ? 1.0 : 0.0;
    }
  }
  for (Eigen::VectorXd& s : out) s /= static_cast<double>(cycles.size());
  return out;
}

// Rows rolled so that row k is row (k + roll) mod rows.
template <typename M>
M rolled(const M& m, Eigen::Index roll) {
  M out(m.rows(), m.cols());
  for (Eigen::Index k = 0; k < m.rows(); ++k) out.row(k) = m.row((k + roll) % m.rows());
  return out;
}

// Per foot, what a planted foot is held at: the change (phases x 3M) averaged over the phases it
// is planted in (stance: per foot, the share of cycles planted at each phase); the posture change
// for a foot never planted.
std::array<Eigen::RowVectorXd, 2> planted_change(const PhaseTable& change, const std::array<Eigen::VectorXd, 2>& stance,
                                                 const Eigen::RowVectorXd& posture) {
  std::array<Eigen::RowVectorXd, 2> out;
  for (size_t side = 0; side < 2; ++side) {
    Eigen::RowVectorXd sum = Eigen::RowVectorXd::Zero(change.cols());
    int n = 0;
    for (Eigen::Index k = 0; k < change.rows(); ++k)
      if (stance[side][k] >= kStanceShare) {
        sum += change.row(k);
        ++n;
      }
    out[side] = n > 0 ? Eigen::RowVectorXd(sum / n) : posture;
  }
  return out;
}

}  // namespace

void StyleChangeOptions::Validate() const {
  if (phases < kMinPhases || phases > kMaxPhases)
    throw InputError("expected from " + std::to_string(kMinPhases) + " to " + std::to_string(kMaxPhases) +
                     " phases in a style's change, found " + std::to_string(phases));
}

StyleChange style_change(const PreparedTakes& p, const Eigen::RowVectorXd& stream_rest,
                         const StyleChangeOptions& options) {
  options.Validate();
  check_takes(p);
  const Eigen::MatrixXd rest = stream_rest;
  const std::vector<double> lengths = bone_lengths(rest, p.parents);
  const int leg[6] = {p.feet.legs[0].hip, p.feet.legs[0].knee, p.feet.legs[0].ankle,
                      p.feet.legs[1].hip, p.feet.legs[1].knee, p.feet.legs[1].ankle};
  const double leg_stream = leg_length(lengths, leg), leg_neutral = leg_length(p.lengths, leg);
  const int phases = options.phases;

  StyleChange out;
  const PreparedTake& neutral_take = p.reference();
  const std::vector<Cycle>& neutral_cycles = neutral_take.cycles.cycles;
  out.cycle_foot = std::max(0, neutral_take.cycles.foot);
  const int other_foot = 1 - out.cycle_foot;
  // Phases matched by foot: in every cycle of every take the other foot strikes at the neutral's
  // mean phase, each side of it linear in time.
  double mean_strike = 0.5;
  const std::vector<double> neutral_strikes =
      other_strikes(neutral_take.own_contacts, neutral_cycles, other_foot, &mean_strike);
  const CanonicalMotion neutral = on_stream_bones(neutral_take.world, p, rest, lengths, leg_stream, leg_neutral);
  const Eigen::MatrixXd neutral_frames = phase_frames(neutral_cycles, neutral_strikes, mean_strike, phases);
  const Eigen::MatrixXd neutral_phases = mean_poses(neutral.local, neutral_frames);
  const Eigen::RowVectorXd neutral_mean = cycles_mean_pose(neutral.local, neutral_take.cycles);
  // Phase 0 is a strike of the cycle foot: a loop's one cycle begins where the clip does, its
  // strike at strike_phase of it, so its phases are rolled on by that much.
  const double shift = neutral_take.cycles.strike_phase;
  const Eigen::Index roll = std::lround(shift * phases) % phases;
  out.other_strike_phase = mean_strike - shift - std::floor(mean_strike - shift);
  out.period_s = neutral_take.cycles.period / p.fps;
  out.stance = stance_by_phase(neutral_take.own_contacts, neutral_cycles, neutral_strikes, mean_strike, phases);
  for (Eigen::VectorXd& s : out.stance) s = rolled(s, roll);
  for (size_t side = 0; side < 2; ++side) out.stance_share[side] = out.stance[side].mean();

  for (size_t i = 1; i < p.takes.size(); ++i) {
    const PreparedTake& t = p.takes[i];
    // The style's frames matching the neutral's, as the alignment matched them (its cycles
    // laid on the neutral's, a smooth warp inside each: align_by_cycles).
    const CanonicalMotion style = on_stream_bones(t.world, p, rest, lengths, leg_stream, leg_neutral);
    const Eigen::MatrixXd style_phases =
        mean_poses(style.local, matched_frames(neutral_frames, neutral_take.frames, t.frames));
    out.cycle.push_back(rolled(periodic_table(style_phases - neutral_phases), roll));
    // Over the style's cycles laid on the neutral's own (not on the slots the neutral plays again
    // where the style has more cycles, cycle_slots.h), as the change by phase is.
    TakeCycles on_own = t.registration.cycles;
    if (on_own.cycles.size() > neutral_cycles.size()) on_own.cycles.resize(neutral_cycles.size());
    out.posture.push_back(cycles_mean_pose(style.local, on_own) - neutral_mean);
    out.planted.push_back(planted_change(out.cycle.back(), out.stance, out.posture.back()));
  }
  return out;
}

}  // namespace mostyle
