#include "engine/align/cycle_phase.h"

#include <cmath>
#include <string>

#include "engine/base/error.h"
#include "engine/prepare/root_path.h"

namespace mostyle {

UnrolledLoop unroll_loop(const CanonicalMotion& take, const Eigen::MatrixXd& contacts, int loop_frames, int repeats) {
  const Eigen::Index frames = take.local.rows();
  if (loop_frames < 2 || (loop_frames != frames && loop_frames != frames - 1))
    throw InputError("a loop of " + std::to_string(loop_frames) + " frames cannot be read across the end of a take of " +
                     std::to_string(frames) + " frames");
  if (repeats < 1) throw InputError("a loop is unrolled at least once, asked " + std::to_string(repeats));
  if (contacts.rows() != frames || contacts.cols() != 2)
    throw InputError("a loop's contacts must be its frames x 2");
  const Eigen::MatrixXd own_steps = root_steps(take);
  UnrolledLoop out;
  out.loop_frames = loop_frames;
  const Eigen::Index total = static_cast<Eigen::Index>(repeats) * loop_frames;
  out.motion.local.resize(total, take.local.cols());
  out.contacts.resize(total, 2);
  Eigen::MatrixXd steps(total, 3);
  for (Eigen::Index v = 0; v < total; ++v) {
    const Eigen::Index f = v % loop_frames;
    out.motion.local.row(v) = take.local.row(f);
    out.contacts.row(v) = contacts.row(f);
    // The step out of the loop's last frame: to the next repeat's first, which the take's own
    // steps hold when its last frame repeats its first; the one before it otherwise.
    const Eigen::Index step_of = f == frames - 1 ? std::max<Eigen::Index>(0, frames - 2) : f;
    steps.row(v) = own_steps.row(step_of);
  }
  integrate_root(steps, take.ground.row(0).transpose(), take.heading[0], &out.motion.ground, &out.motion.heading);
  return out;
}

TakeCycles cycles_at_phase(const TakeCycles& take, double phase, int frames) {
  TakeCycles out = take;
  out.cycles.clear();
  out.strike_phase = phase;
  const size_t n = take.cycles.size();
  auto shift_of = [&](const Cycle& c) {
    return static_cast<int>(std::lround((take.strike_phase - phase) * c.frames()));
  };
  auto fits = [&](const Cycle& c) { return c.begin >= 0 && c.end > c.begin && c.end < frames; };
  for (size_t k = 0; k < n; ++k) {
    const Cycle& c = take.cycles[k];
    const bool meets = k + 1 < n && take.cycles[k + 1].begin == c.end;
    Cycle moved{c.begin + shift_of(c), meets ? c.end + shift_of(take.cycles[k + 1]) : c.end + shift_of(c)};
    if (!fits(moved)) continue;
    if (!out.cycles.empty() && moved.begin < out.cycles.back().end) continue;
    out.cycles.push_back(moved);
  }
  if (out.cycles.empty()) {
    // No moved cycle fits where it is: one cycle moved a whole cycle on or back, where it fits.
    for (size_t k = 0; k < n && out.cycles.empty(); ++k) {
      const Cycle& c = take.cycles[k];
      for (int way : {1, -1}) {
        const int by = shift_of(c) + way * c.frames();
        const Cycle moved{c.begin + by, c.end + by};
        if (fits(moved)) {
          out.cycles.push_back(moved);
          break;
        }
      }
    }
  }
  if (out.cycles.empty()) {
    out.kind = CycleKind::kNone;
    out.reason = "no whole cycle of it begins at the reference's phase within its frames";
  }
  return out;
}

}  // namespace mostyle
