#pragma once
// A leg placed where a two-bone IK solve puts it, as the clean-up passes move legs (the foot
// lock, the swing clearance): the knee and ankle set, the toe moved with the ankle (the foot
// translated, its length and pitch kept).
#include <Eigen/Core>

#include "engine/kinematics/joint_rows.h"
#include "engine/kinematics/two_bone_ik.h"
#include "engine/measure/foot_contact.h"

namespace mostyle {

// world: positions (rows frames, 3 columns a joint; any Eigen matrix); t: the frame.
template <typename Matrix>
void place_leg(Matrix& world, Eigen::Index t, const LegColumns& leg, const TwoBoneIkResult& solved) {
  const Eigen::Vector3d ankle = joint_at(world, t, leg.ankle);
  set_joint(world, t, leg.knee, solved.mid);
  set_joint(world, t, leg.ankle, solved.end);
  if (leg.toe >= 0) set_joint(world, t, leg.toe, joint_at(world, t, leg.toe) + (solved.end - ankle));
}

}  // namespace mostyle
