#include "engine/kinematics/units.h"

#include <algorithm>
#include <cmath>

#include "engine/kinematics/kinematics.h"

namespace mostyle {

UnitsGuess guess_units(const Clip& clip) {
  std::vector<Eigen::Vector3d> points;
  if (clip.frames() > 0) {
    points = pose_at(clip, 0).positions;
  } else {
    points = rest_positions(clip.skeleton);
  }
  UnitsGuess g;
  if (points.empty()) return g;
  Eigen::Vector3d lo = points[0], hi = points[0];
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  g.height = hi.y() - lo.y();
  g.size = (hi - lo).norm();
  // A standing person is 1.5 to 1.9 m: the unit in which the height falls in that band.
  struct Band {
    double lo, hi;
    const char* name;
  };
  static const Band kBands[] = {{0.9, 2.5, "metres"},
                                {2.5, 7.0, "feet"},
                                {7.0, 45.0, "CMU units (1/0.45 inch)"},
                                {45.0, 90.0, "inches"},
                                {90.0, 300.0, "centimetres"},
                                {900.0, 3000.0, "millimetres"}};
  g.name = "unknown";
  for (const Band& b : kBands) {
    if (g.height >= b.lo && g.height < b.hi) g.name = b.name;
  }
  return g;
}

double centimetres_per_unit(const std::string& unit_name) {
  // The names of guess_units' bands.
  if (unit_name == "metres") return 100.0;
  if (unit_name == "feet") return 30.48;
  if (unit_name == "CMU units (1/0.45 inch)") return 2.54 / 0.45;
  if (unit_name == "inches") return 2.54;
  if (unit_name == "centimetres") return 1.0;
  if (unit_name == "millimetres") return 0.1;
  return 0.0;
}

double metres_per_unit(const Clip& clip) {
  if (clip.skeleton.metres_per_unit > 0.0 && std::isfinite(clip.skeleton.metres_per_unit))
    return clip.skeleton.metres_per_unit;
  return centimetres_per_unit(guess_units(clip).name) / 100.0;
}

double motion_height(const Eigen::MatrixXd& positions) {
  const Eigen::Index joints = positions.cols() / 3;
  double size = 0.0;
  for (Eigen::Index f = 0; f < positions.rows(); ++f) {
    double lo = 0.0, hi = 0.0;
    for (Eigen::Index j = 0; j < joints; ++j) {
      const double y = positions(f, 3 * j + 1);
      if (j == 0 || y < lo) lo = y;
      if (j == 0 || y > hi) hi = y;
    }
    size = std::max(size, hi - lo);
  }
  return size;
}

}  // namespace mostyle
