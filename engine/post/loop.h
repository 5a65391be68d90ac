#pragma once
// Loopable cycles: a whole number of gait cycles cut from a blend at
// left-foot strikes, with the seam closed so the clip plays seamlessly on repeat while the root
// keeps its travel per cycle (root motion).
#include <Eigen/Core>

namespace mostyle {

constexpr int kLoopMaxCycles = 4;
// Candidate cycles that turn more than this (radians) are passed over while straighter ones exist.
constexpr double kLoopMaxTurn = 0.6;

struct LoopCut {
  int begin = 0, end = 0;   // output frames [begin, end): frame `end` would repeat `begin`
  int cycles = 0;           // gait cycles (left-foot strike to left-foot strike) in the loop
  Eigen::Vector2d travel = Eigen::Vector2d::Zero();  // root (x, z) travel per loop, file units, world
  double turn_removed = 0.0;  // radians of heading change spread out so the loop walks straight
  int frames() const { return end - begin; }
};

// Chooses the loop from contacts (F x 2, left and right foot; left-foot strikes, else right)
// and local poses (F x 3M, canonical frame): of the spans of 1 to kLoopMaxCycles cycles between
// strikes, the one whose end pose is closest to its start pose (slightly favouring more
// cycles), among those that turn less than kLoopMaxTurn. Throws InputError when the motion has
// fewer than two strikes of either foot (no whole cycle). O(strikes x cycles x M).
LoopCut find_loop(const Eigen::MatrixXd& contacts, const Eigen::MatrixXd& local, const Eigen::VectorXd& heading);

// Cuts [begin, end) out of the blend and closes the seam, in place: local poses get the
// difference between the pose at `end` and at `begin` spread linearly over the cycle (so the
// last frame leads into the first as any frame into the next), and the root's heading change
// is spread out the same way, its steps re-integrated from frame `begin` (travel kept).
// local: F x 3M, ground: F x 2, heading: F, contacts: F x 2; each becomes cut.frames() rows.
// Sets cut.travel and cut.turn_removed. O(F x M).
void close_loop(LoopCut& cut, Eigen::MatrixXd& local, Eigen::MatrixXd& ground, Eigen::VectorXd& heading,
                Eigen::MatrixXd& contacts);

}  // namespace mostyle
