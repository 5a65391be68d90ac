#include "ui/lanes.h"

#include <algorithm>

namespace mostyle::ui {

Lanes lanes_along(const Eigen::MatrixXd& world, const Eigen::Vector2d& fallback, int half_window) {
  Lanes lanes;
  const Eigen::Index frames = world.rows();
  lanes.path.resize(frames, 2);
  lanes.across.resize(frames, 2);
  if (frames == 0) return lanes;
  lanes.path.col(0) = world.col(0);
  lanes.path.col(1) = world.col(2);
  Eigen::Vector2d previous = fallback.normalized();
  for (Eigen::Index t = 0; t < frames; ++t) {
    const Eigen::Index a = std::max<Eigen::Index>(0, t - half_window), b = std::min(frames - 1, t + half_window);
    const Eigen::Vector2d travel = (lanes.path.row(b) - lanes.path.row(a)).transpose();
    // Across = (travel.z, -travel.x): the side the editor's fixed layout used (blend_session).
    Eigen::Vector2d across(travel.y(), -travel.x());
    if (across.norm() > 1e-9) previous = across.normalized();
    lanes.across.row(t) = previous.transpose();
  }
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
