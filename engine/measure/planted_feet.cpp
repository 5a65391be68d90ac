#include "engine/measure/planted_feet.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/base/error.h"
#include "engine/prepare/major_skeleton.h"
#include "engine/prepare/major_take.h"

namespace mostyle {

std::array<int, kFootJoints> foot_joint_columns(const FootRig& rig) {
  std::array<int, kFootJoints> out;
  for (int side = 0; side < 2; ++side) {
    const LegColumns& leg = rig.legs[static_cast<size_t>(side)];
    out[static_cast<size_t>(2 * side)] = leg.usable() ? leg.ankle : -1;
    out[static_cast<size_t>(2 * side + 1)] = leg.usable() ? leg.toe : -1;
  }
  return out;
}

void planted_frames(const Eigen::MatrixXd& world, const FootRig& rig, Eigen::MatrixXd& planted,
                    std::vector<double>& heights, std::array<double, kFootJoints>* floors, double band_scale) {
  if (!(rig.body_height > 0.0) || !std::isfinite(rig.body_height))
    throw InputError("planted feet: expected a positive body height, found " + std::to_string(rig.body_height));
  const Eigen::Index frames = world.rows();
  planted.setZero(frames, kFootJoints);
  if (floors != nullptr) floors->fill(0.0);
  if (frames == 0) return;
  const double band = band_scale * kPlantedHeightFraction * rig.body_height;
  const std::array<int, kFootJoints> columns = foot_joint_columns(rig);
  heights.resize(static_cast<size_t>(frames));
  for (int j = 0; j < kFootJoints; ++j) {
    const int c = columns[static_cast<size_t>(j)];
    if (c < 0) continue;
    if (3 * static_cast<Eigen::Index>(c) + 2 >= world.cols())
      throw InputError("planted feet: positions have " + std::to_string(world.cols()) +
                       " columns, too few for joint column " + std::to_string(c));
    for (Eigen::Index t = 0; t < frames; ++t) heights[static_cast<size_t>(t)] = world(t, 3 * c + 1);
    // The joint's own floor: a low percentile of its heights, so a take whose ground is not at 0,
    // or whose ankle sits high above the sole, needs no setting.
    const size_t k = static_cast<size_t>(kPlantedFloorPercentile * static_cast<double>(frames - 1));
    std::nth_element(heights.begin(), heights.begin() + static_cast<std::ptrdiff_t>(k), heights.end());
    const double floor = heights[k];
    if (floors != nullptr) (*floors)[static_cast<size_t>(j)] = floor;
    for (Eigen::Index t = 0; t < frames; ++t) planted(t, j) = world(t, 3 * c + 1) - floor <= band ? 1.0 : 0.0;
  }
}

PlantedSpeed planted_speed(const Eigen::MatrixXd& world, const Eigen::MatrixXd& planted, const FootRig& rig) {
  if (planted.rows() != world.rows() || planted.cols() != kFootJoints)
    throw InputError("planted feet: expected " + std::to_string(world.rows()) + " x " + std::to_string(kFootJoints) +
                     " planted frames, found " + std::to_string(planted.rows()) + " x " +
                     std::to_string(planted.cols()));
  const std::array<int, kFootJoints> columns = foot_joint_columns(rig);
  PlantedSpeed out;
  out.height = rig.body_height;
  double sum = 0.0;
  for (int j = 0; j < kFootJoints; ++j) {
    const int c = columns[static_cast<size_t>(j)];
    if (c < 0) continue;
    for (Eigen::Index t = 0; t + 1 < world.rows(); ++t) {
      if (planted(t, j) <= 0.5 || planted(t + 1, j) <= 0.5) continue;
      sum += horizontal_step(world(t + 1, 3 * c) - world(t, 3 * c), world(t + 1, 3 * c + 2) - world(t, 3 * c + 2));
      ++out.steps;
    }
  }
  out.speed = out.steps > 0 ? sum * rig.fps / static_cast<double>(out.steps) : 0.0;
  return out;
}

PlantedSpeed planted_speed(const Eigen::MatrixXd& world, const FootRig& rig) {
  Eigen::MatrixXd planted;
  std::vector<double> heights;
  planted_frames(world, rig, planted, heights);
  return planted_speed(world, planted, rig);
}

double standing_height(const std::vector<int>& majors, const std::vector<double>& lengths) {
  auto length = [&](MajorJoint j) {
    const int c = major_column(majors, static_cast<int>(j));
    return c >= 0 && static_cast<size_t>(c) < lengths.size() ? lengths[static_cast<size_t>(c)] : -1.0;
  };
  double legs = 0.0;
  int usable = 0;
  for (const auto& [knee, ankle] : {std::pair{MajorJoint::kLeftKnee, MajorJoint::kLeftAnkle},
                                    std::pair{MajorJoint::kRightKnee, MajorJoint::kRightAnkle}}) {
    const double thigh = length(knee), shin = length(ankle);
    if (thigh < 0.0 || shin < 0.0) continue;
    legs += thigh + shin;
    ++usable;
  }
  if (usable == 0) return 0.0;
  double trunk = 0.0;
  for (MajorJoint j : {MajorJoint::kSpine, MajorJoint::kChest, MajorJoint::kHead}) trunk += std::max(0.0, length(j));
  return legs / usable + trunk;
}

}  // namespace mostyle
