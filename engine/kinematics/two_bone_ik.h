#pragma once
// Two-bone IK on joint positions, as a job (after ozz-animation's IKTwoBoneJob: named inputs,
// Validate(), Run() giving a named result): a chain of three joints (a leg's hip, knee and
// ankle) whose end is moved to a target, the start staying, both bones keeping their lengths and
// the middle joint bending towards a pole. The foot lock, the swing clearance, the stride warp
// and the live styler move legs with it.
#include <Eigen/Core>

namespace mostyle {

// A bend (the middle joint off the line from the start to the target) shorter than this fraction
// of the chain's length has no direction of its own.
constexpr double kStraightChain = 1e-4;
// The fraction of the chain's length the solve keeps short of full extension and full folding:
// there the middle joint's distance from the start-target line is the square root of a
// difference that vanishes, so rounding in the input would move it by the square root of
// rounding (1e-8 of the chain, not 1e-16).
constexpr double kChainMargin = 1e-9;

struct TwoBoneIkResult {
  Eigen::Vector3d mid = Eigen::Vector3d::Zero();  // the middle joint's new position
  Eigen::Vector3d end = Eigen::Vector3d::Zero();  // the end's: the target, or the nearest point in reach
  bool reached = false;  // the end is at the target: the target lies within the chain's reach
};

struct TwoBoneIkJob {
  // The chain as it is, in any one unit: its bones are |mid - start| and |end - mid|.
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d mid = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  Eigen::Vector3d target = Eigen::Vector3d::Zero();  // where the end should go
  // Which way the middle joint bends: its part perpendicular to the start-target line (the
  // chain's own bend is mid - start).
  Eigen::Vector3d pole = Eigen::Vector3d::Zero();
  // The bend where the pole's perpendicular part is shorter than kStraightChain of the chain (a
  // straight chain, a pole along the line); where this one's is zero too, any perpendicular.
  Eigen::Vector3d bend_fallback = Eigen::Vector3d::Zero();

  bool Validate() const;  // false when an input is not finite
  // The end on the start-target line, at the target's distance clamped to what the bones reach
  // (kChainMargin short of straight or folded), the middle joint where both bones keep their
  // lengths, on the pole's side (law of cosines). A target within kStraightChain of the chain
  // from the start gives no direction: the chain as it is, not reached; as does a job that does
  // not validate. O(1).
  TwoBoneIkResult Run() const;
};

}  // namespace mostyle
