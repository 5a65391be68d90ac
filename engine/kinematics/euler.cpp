#include "engine/kinematics/euler.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>

#include "engine/kinematics/four_lanes.h"

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

namespace {

// sin_cos_degrees's arithmetic on four angles at once, operation for operation (so the values are
// the same bit for bit); a group holding an angle sin_cos_degrees does not reduce (huge, not a
// number) goes one at a time. Inlined into each of the functions below, which compile it for
// their instruction sets.
inline __attribute__((always_inline)) void sin_cos_fours(const double* degrees, size_t n, double* sine,
                                                         double* cosine) {
  using namespace sin_cos_terms;
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    Doubles4 d;
    std::memcpy(&d, degrees + i, sizeof d);
    const Doubles4 size = d < 0.0 ? -d : d;
    const Integers4 reduced = size <= kLargestReducedDegrees;  // false for NaN
    if (!(reduced[0] && reduced[1] && reduced[2] && reduced[3])) {
      for (size_t k = i; k < i + 4; ++k) sin_cos_degrees(degrees[k], sine + k, cosine + k);
      continue;
    }
    const Doubles4 q = d * (1.0 / 90.0);
    const Doubles4 half = q >= 0.0 ? Doubles4{0.5, 0.5, 0.5, 0.5} : Doubles4{-0.5, -0.5, -0.5, -0.5};
    const Integers4 turns = __builtin_convertvector(q + half, Integers4);
    const Doubles4 r = (d - __builtin_convertvector(turns, Doubles4) * 90.0) * (3.14159265358979323846 / 180.0);
    const Doubles4 r2 = r * r, r4 = r2 * r2, r8 = r4 * r4;
    const Doubles4 s =
        r * ((1.0 - k3 * r2) + r4 * (k5 - k7 * r2) + r8 * ((k9 - k11 * r2) + r4 * (k13 - k15 * r2) + r8 * k17));
    const Doubles4 c = (1.0 - k2 * r2) + r4 * (k4 - k6 * r2) + r8 * ((k8 - k10 * r2) + r4 * (k12 - k14 * r2) + r8 * k16);
    const Integers4 odd = (turns & 1) != 0;
    const Doubles4 out_s = (odd ? c : s) * (1.0 - __builtin_convertvector(turns & 2, Doubles4));
    const Doubles4 out_c = (odd ? s : c) * (1.0 - __builtin_convertvector((turns + 1) & 2, Doubles4));
    std::memcpy(sine + i, &out_s, sizeof out_s);
    std::memcpy(cosine + i, &out_c, sizeof out_c);
  }
  for (; i < n; ++i) sin_cos_degrees(degrees[i], sine + i, cosine + i);
}

#if defined(__x86_64__)
__attribute__((target("avx2"))) void sin_cos_avx2(const double* degrees, size_t n, double* sine, double* cosine) {
  sin_cos_fours(degrees, n, sine, cosine);
}
#endif

void sin_cos_baseline(const double* degrees, size_t n, double* sine, double* cosine) {
  sin_cos_fours(degrees, n, sine, cosine);
}

}  // namespace

// Chosen at the first call, not by the loader (an ifunc resolver runs before the sanitizers'
// runtimes are up and crashes them).
void sin_cos_degrees_n(const double* degrees, size_t n, double* sine, double* cosine) {
#if defined(__x86_64__)
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) return sin_cos_avx2(degrees, n, sine, cosine);
#endif
  sin_cos_baseline(degrees, n, sine, cosine);
}

Eigen::Matrix3d axis_rotation(int axis, double degrees) {
  double s, c;
  sin_cos_degrees(degrees, &s, &c);
  return axis_rotation(axis, s, c);
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
