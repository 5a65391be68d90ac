#pragma once
// A made-up walker for the canonical frame and root path tests: five joints (hips, left hip, right
// hip, left foot, head) walking a path that turns as asked, any units.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace mostyle::test {

// World positions of a walker with joints hips (0), left hip (1), right hip (2), left foot (3),
// head (4): hips at ground (x, z) and height 90, facing `heading` (0: +Z, pi/2: +X), the left
// foot swinging forward and back with `phase`.
inline Eigen::RowVectorXd walker(double x, double z, double heading, double phase) {
  const double c = std::cos(heading), s = std::sin(heading);
  // Body frame (right-handed, Y up, facing +Z): left is +X.
  const Eigen::Vector3d local[5] = {{0, 90, 0},
                                    {9, 88, 0},
                                    {-9, 88, 0},
                                    {9, 5 + 3 * std::max(0.0, std::sin(phase)), 20 * std::sin(phase)},
                                    {1, 160, 2}};
  Eigen::RowVectorXd row(15);
  for (int j = 0; j < 5; ++j) {
    // R_y(heading): x = c lx + s lz, z = -s lx + c lz.
    row(3 * j) = x + c * local[j].x() + s * local[j].z();
    row(3 * j + 1) = local[j].y();
    row(3 * j + 2) = z - s * local[j].x() + c * local[j].z();
  }
  return row;
}

// A path of `frames` frames: per frame the walker moves `speed` forward and turns by turn(t).
template <typename Turn>
Eigen::MatrixXd walk(int frames, double x, double z, double heading, double speed, Turn turn) {
  Eigen::MatrixXd world(frames, 15);
  for (int t = 0; t < frames; ++t) {
    world.row(t) = walker(x, z, heading, 0.3 * t);
    x += speed * std::sin(heading);
    z += speed * std::cos(heading);
    heading += turn(t);
  }
  return world;
}

// Walks 40 frames, turns 180 degrees in place (to the left, heading increasing) over 20, walks
// back 40.
inline Eigen::MatrixXd walk_with_u_turn(double x, double z, double heading, double direction = 1.0) {
  return walk(100, x, z, heading, 1.5, [direction](int t) {
    return t >= 40 && t < 60 ? direction * M_PI / 20 : 0.0;
  });
}

}  // namespace mostyle::test
