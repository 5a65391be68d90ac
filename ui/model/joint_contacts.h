#pragma once
// The engine's foot contacts (F x 2, left and right foot) as the viewport's per-joint contacts
// (Take::contacts, frames x joints): the ankle and toe columns of each planted foot.
#include <Eigen/Core>

#include "engine/measure/foot_contact.h"

namespace mostyle::ui {

inline Eigen::MatrixXd joint_contacts(const Eigen::MatrixXd& feet, const FootRig& rig, int joints) {
  Eigen::MatrixXd out;
  if (feet.rows() == 0 || feet.cols() < 2) return out;
  out = Eigen::MatrixXd::Zero(feet.rows(), joints);
  for (int side = 0; side < 2; ++side) {
    for (int column : {rig.legs[side].ankle, rig.legs[side].toe}) {
      if (column < 0 || column >= joints) continue;
      out.col(column) = (feet.col(side).array() > 0.5).cast<double>().matrix();
    }
  }
  return out;
}

}  // namespace mostyle::ui
