#include "engine/kinematics/euler.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace mostyle {
namespace {

constexpr double kDegrees = 180.0 / M_PI;
constexpr double kGimbalCos = 1e-9;  // cos(middle angle) below this: gimbal lock

double wrap_near(double angle, double target) {
  return angle + 360.0 * std::round((target - angle) / 360.0);
}

// Of the two Euler solutions, each angle wrapped near `previous`, the closer one.
Eigen::Vector3d nearest_solution(const Eigen::Vector3d& first, const Eigen::Vector3d& previous) {
  const Eigen::Vector3d second(first[0] + 180.0, 180.0 - first[1], first[2] + 180.0);
  Eigen::Vector3d best = first;
  double best_distance = INFINITY;
  for (const Eigen::Vector3d& candidate : {first, second}) {
    Eigen::Vector3d shifted;
    for (int d = 0; d < 3; ++d) shifted[d] = wrap_near(candidate[d], previous[d]);
    const double distance = (shifted - previous).squaredNorm();
    if (distance < best_distance) {
      best_distance = distance;
      best = shifted;
    }
  }
  return best;
}

// |cos| of the middle angle of R in the order with axes (i, j, k).
double middle_cos(const Eigen::Matrix3d& R, int i, int j) {
  return std::sqrt(R(i, i) * R(i, i) + R(i, j) * R(i, j));
}

// +1 for the cyclic orders (XYZ, YZX, ZXY), -1 for the others.
double order_sign(int i, int j) { return ((j - i + 3) % 3 == 1) ? 1.0 : -1.0; }

// The first angle, in radians, of R = Ri(a) Rj(+-90): rows j and k of R hold only a then.
double gimbal_first_angle(const Eigen::Matrix3d& R, int i, int j, int k) {
  return std::atan2(order_sign(i, j) * R(k, j), R(j, j));
}

}  // namespace

std::array<int, 3> euler_axes(EulerOrder order) {
  switch (order) {
    case EulerOrder::kXYZ: return {0, 1, 2};
    case EulerOrder::kXZY: return {0, 2, 1};
    case EulerOrder::kYXZ: return {1, 0, 2};
    case EulerOrder::kYZX: return {1, 2, 0};
    case EulerOrder::kZXY: return {2, 0, 1};
    case EulerOrder::kZYX: return {2, 1, 0};
  }
  return {0, 1, 2};
}

std::string euler_order_name(EulerOrder order) {
  std::string s;
  for (int a : euler_axes(order)) s += static_cast<char>('X' + a);
  return s;
}

bool parse_euler_order(std::string_view text, EulerOrder* order) {
  if (text.size() != 3) return false;
  std::string upper;
  for (char c : text) upper += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  for (EulerOrder o : {EulerOrder::kXYZ, EulerOrder::kXZY, EulerOrder::kYXZ, EulerOrder::kYZX,
                       EulerOrder::kZXY, EulerOrder::kZYX}) {
    if (euler_order_name(o) == upper) {
      *order = o;
      return true;
    }
  }
  return false;
}

Eigen::Matrix3d axis_rotation(int axis, double degrees) {
  double s, c;
  sin_cos_degrees(degrees, &s, &c);
  Eigen::Matrix3d m;
  switch (axis) {
    case 0: m << 1, 0, 0, 0, c, -s, 0, s, c; break;
    case 1: m << c, 0, s, 0, 1, 0, -s, 0, c; break;
    default: m << c, -s, 0, s, c, 0, 0, 0, 1; break;
  }
  return m;
}

Eigen::Matrix3d euler_to_matrix(EulerOrder order, const Eigen::Vector3d& angles) {
  const auto ax = euler_axes(order);
  return axis_rotation(ax[0], angles[0]) * axis_rotation(ax[1], angles[1]) *
         axis_rotation(ax[2], angles[2]);
}

Eigen::Vector3d matrix_to_euler(EulerOrder order, const Eigen::Matrix3d& R) {
  // R = Ri(a) Rj(b) Rk(c) with (i, j, k) the order's axes; s = +1 for cyclic (even) orders.
  const auto ax = euler_axes(order);
  const int i = ax[0], j = ax[1], k = ax[2];
  const double s = order_sign(i, j);
  // atan2 rather than asin: asin loses half the digits near +-90 degrees, where CMU roots live.
  const double cb = middle_cos(R, i, j);
  const double b = std::atan2(std::clamp(s * R(i, k), -1.0, 1.0), cb);
  double a, c;
  if (cb > kGimbalCos) {
    a = std::atan2(-s * R(j, k), R(k, k));
    c = std::atan2(-s * R(i, j), R(i, i));
  } else {
    // Gimbal lock: only a +- c is defined; put it all in a.
    c = 0.0;
    a = gimbal_first_angle(R, i, j, k);
  }
  return Eigen::Vector3d(a, b, c) * kDegrees;
}

Eigen::Vector3d matrix_to_euler_near(EulerOrder order, const Eigen::Matrix3d& rotation,
                                     const Eigen::Vector3d& previous) {
  const auto ax = euler_axes(order);
  if (middle_cos(rotation, ax[0], ax[1]) <= kGimbalCos) {
    // Gimbal lock: any split of the outer angles is right. Keep the third angle where it was and
    // solve the first from R * Rk(-c), which is then Ri(a) Rj(b) exactly.
    const double c = previous[2];
    const Eigen::Matrix3d m = rotation * axis_rotation(ax[2], -c);
    const double a = gimbal_first_angle(m, ax[0], ax[1], ax[2]) * kDegrees;
    const double b = matrix_to_euler(order, rotation)[1];
    return Eigen::Vector3d(wrap_near(a, previous[0]), wrap_near(b, previous[1]), c);
  }
  return nearest_solution(matrix_to_euler(order, rotation), previous);
}

Eigen::Vector3d euler_near(const Eigen::Vector3d& angles, const Eigen::Vector3d& previous) {
  return nearest_solution(angles, previous);
}

}  // namespace mostyle
