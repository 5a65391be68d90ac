#include "engine/post/loop.h"

#include <cmath>
#include <limits>
#include <vector>

#include "engine/base/error.h"
#include "engine/measure/foot_contact.h"
#include "engine/prepare/root_path.h"

namespace mostyle {

LoopCut find_loop(const Eigen::MatrixXd& contacts, const Eigen::MatrixXd& local, const Eigen::VectorXd& heading) {
  std::vector<int> onsets = foot_strikes(contacts, 0);
  if (onsets.size() < 2) onsets = foot_strikes(contacts, 1);
  if (onsets.size() < 2)
    throw InputError("cannot cut a loop: the blend has fewer than two foot strikes of either foot (no whole gait cycle)");
  LoopCut best;
  double best_score = std::numeric_limits<double>::infinity();
  bool best_straight = false;
  for (size_t p = 0; p < onsets.size(); ++p)
    for (int c = 1; c <= kLoopMaxCycles && p + c < onsets.size(); ++c) {
      const int s = onsets[p], e = onsets[p + c];
      const double turn = std::abs(heading[e] - heading[s]);
      const bool straight = turn <= kLoopMaxTurn;
      const double distance = (local.row(e) - local.row(s)).norm();
      const double score = distance * (1.0 + 0.05 * (kLoopMaxCycles - c));
      if ((straight && !best_straight) || (straight == best_straight && score < best_score)) {
        best_score = score;
        best_straight = straight;
        best.begin = s;
        best.end = e;
        best.cycles = c;
      }
    }
  return best;
}

void close_loop(LoopCut& cut, Eigen::MatrixXd& local, Eigen::MatrixXd& ground, Eigen::VectorXd& heading,
                Eigen::MatrixXd& contacts) {
  const int s = cut.begin, e = cut.end, n = e - s;
  if (s < 0 || n < 1 || e >= local.rows()) throw InputError("a loop must lie inside the blend");
  const Eigen::RowVectorXd gap = local.row(s) - local.row(e);
  Eigen::MatrixXd cut_local = local.middleRows(s, n);
  for (int t = 0; t < n; ++t) cut_local.row(t) += (double(t) / n) * gap;
  // Root: steps over s..e, the turn spread so the heading comes back, re-integrated.
  Eigen::MatrixXd steps = root_steps(ground.middleRows(s, n + 1), heading.segment(s, n + 1));
  cut.turn_removed = heading[e] - heading[s];
  for (int t = 0; t < n; ++t) steps(t, 2) -= cut.turn_removed / n;
  Eigen::MatrixXd g;
  Eigen::VectorXd h;
  integrate_root(steps, ground.row(s).transpose(), heading[s], &g, &h);
  cut.travel = (g.row(n) - g.row(0)).transpose();
  local = cut_local;
  ground = g.topRows(n);
  heading = h.head(n);
  contacts = contacts.middleRows(s, n).eval();
}

}  // namespace mostyle
