#include "engine/retarget.h"

#include <cmath>

#include "engine/error.h"
#include "engine/limb_length.h"

namespace mostyle {

double leg_length(const std::vector<double>& lengths, const int (&leg_joints)[6]) {
  // Thigh = length of the knee's bone, shin = length of the ankle's bone.
  return 0.5 * (lengths[leg_joints[1]] + lengths[leg_joints[2]] + lengths[leg_joints[4]] +
                lengths[leg_joints[5]]);
}

Eigen::MatrixXd retarget_positions(const Eigen::MatrixXd& world_b, const std::vector<int>& parents,
                                   const std::vector<double>& lengths_a, double leg_a, double leg_b) {
  if (!(leg_a > 0) || !(leg_b > 0) || !std::isfinite(leg_a / leg_b))
    throw InputError("cannot retarget: a take has legs of zero length");
  // A uniform scale keeps every bone direction; the limb pass then fixes each length exactly.
  Eigen::MatrixXd out = world_b * (leg_a / leg_b);
  apply_limb_lengths(out, parents, lengths_a);
  return out;
}

}  // namespace mostyle
