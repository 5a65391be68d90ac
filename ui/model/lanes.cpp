#include "ui/model/lanes.h"

#include <algorithm>

#include "engine/kinematics/units.h"

namespace mostyle::ui {

Placement placement_of(const Eigen::MatrixXd& w, float spacing_factor) {
  Placement p;
  const Eigen::Index joints = w.cols() / 3;
  if (w.rows() == 0 || joints == 0) return p;
  double lowest = w.col(1).minCoeff();
  for (Eigen::Index j = 1; j < joints; ++j) lowest = std::min(lowest, w.col(3 * j + 1).minCoeff());
  Eigen::Vector3d start = Eigen::Vector3d::Zero(), end = Eigen::Vector3d::Zero();
  for (Eigen::Index j = 0; j < joints; ++j) {
    start += w.row(0).segment<3>(3 * j).transpose();
    end += w.row(w.rows() - 1).segment<3>(3 * j).transpose();
  }
  start /= double(joints);
  end /= double(joints);
  p.shift = Eigen::Vector3d(-start.x(), -lowest, -start.z());
  p.size = static_cast<float>(motion_height(w));
  p.spacing = spacing_factor * (p.size > 0.0f ? p.size : 1.0f);
  const Eigen::Vector2d travel(end.x() - start.x(), end.z() - start.z());
  if (travel.norm() > 1e-9) p.side = Eigen::Vector3d(travel.y(), 0.0, -travel.x()).normalized();
  return p;
}

Lanes lanes_along(const Eigen::MatrixXd& world, const Eigen::Vector2d& fallback) {
  Lanes lanes;
  const Eigen::Index frames = world.rows();
  lanes.path.resize(frames, 2);
  lanes.across.resize(frames, 2);
  if (frames == 0) return lanes;
  lanes.path.col(0) = world.col(0);
  lanes.path.col(1) = world.col(2);
  // One direction across for the whole take (the reference's overall travel, which the camera's
  // three-quarter view is chosen from): lanes that turned with every sway of the path would line
  // the takes up along the view.
  const Eigen::Vector2d across = fallback.norm() > 1e-12 ? fallback.normalized() : Eigen::Vector2d::UnitX();
  lanes.across.rowwise() = across.transpose();
  return lanes;
}

void place_in_lane(const Eigen::MatrixXd& world, const Lanes& lanes, double offset, const Eigen::Vector3d& shift,
                   Eigen::MatrixXd& out) {
  out = world;
  const Eigen::Index frames = world.rows();
  if (frames == 0 || lanes.path.rows() == 0) return;
  for (Eigen::Index t = 0; t < frames; ++t) {
    const Eigen::Index l = std::min(t, lanes.path.rows() - 1);
    const double x = lanes.path(l, 0) + offset * lanes.across(l, 0) - world(t, 0);
    const double z = lanes.path(l, 1) + offset * lanes.across(l, 1) - world(t, 2);
    for (Eigen::Index j = 0; 3 * j < out.cols(); ++j) {
      out(t, 3 * j) += x + shift.x();
      out(t, 3 * j + 1) += shift.y();
      out(t, 3 * j + 2) += z + shift.z();
    }
  }
}

}  // namespace mostyle::ui
