#pragma once
// Euler angles in the six Tait-Bryan orders BVH files use, in degrees.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <string>
#include <string_view>

namespace mostyle {

// Named as the channels appear: kZXY is "Zrotation Xrotation Yrotation", R = Rz * Rx * Ry.
enum class EulerOrder { kXYZ, kXZY, kYXZ, kYZX, kZXY, kZYX };

// Axis indices 0..2 in channel order. Inline: the resampler and FK ask once per joint and frame.
inline std::array<int, 3> euler_axes(EulerOrder order) {
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
std::string euler_order_name(EulerOrder order);   // "ZXY"
bool parse_euler_order(std::string_view text, EulerOrder* order);  // "zxy" too; false if not one

// The sine and cosine of an angle in degrees, within two units in the last place of the exact
// values: the angle is reduced to [-45, 45] degrees about a multiple of 90 (exactly, for angles
// under 2^40 degrees), whose sines and cosines are exact (sin 90 is 1, cos 90 is 0), then
// polynomials of its radians. Several times faster than std::sin and std::cos of the radians:
// forward kinematics takes three of each per joint and frame. Not finite: NaN.
inline void sin_cos_degrees(double degrees, double* sine, double* cosine);

// sin_cos_degrees of n angles at once, the same values bit for bit, four at a time on a CPU with
// AVX2 (several times faster than one at a time: batches of forward kinematics use it).
void sin_cos_degrees_n(const double* degrees, size_t n, double* sine, double* cosine);

// Rotation about axis 0, 1 or 2 by `degrees` (right-handed).
Eigen::Matrix3d axis_rotation(int axis, double degrees);
// The same, from the angle's sine and cosine (sin_cos_degrees).
inline Eigen::Matrix3d axis_rotation(int axis, double s, double c) {
  Eigen::Matrix3d m;
  switch (axis) {
    case 0: m << 1, 0, 0, 0, c, -s, 0, s, c; break;
    case 1: m << c, 0, s, 0, 1, 0, -s, 0, c; break;
    default: m << c, -s, 0, s, c, 0, 0, 0, 1; break;
  }
  return m;
}

// angles: degrees, in the order's channel order (for kZXY: z, x, y).
Eigen::Matrix3d euler_to_matrix(EulerOrder order, const Eigen::Vector3d& angles);

// The angles of R (a rotation matrix) in `order`, middle angle in [-90, 90], others in
// [-180, 180]. At gimbal lock (middle angle +-90) only the sum or difference of the outer two is
// defined: the third angle is then 0.
Eigen::Vector3d matrix_to_euler(EulerOrder order, const Eigen::Matrix3d& rotation);

// The equivalent angles of R closest to `previous` (both Euler solutions, each angle shifted by
// multiples of 360; at gimbal lock the third angle stays at `previous`'s), so a curve has no
// jumps over 180 degrees between frames.
Eigen::Vector3d matrix_to_euler_near(EulerOrder order, const Eigen::Matrix3d& rotation,
                                     const Eigen::Vector3d& previous);

// The same rotation as `angles` (any order: (a, b, c) and (a+180, 180-b, c+180), each shifted by
// multiples of 360) closest to `previous`. Exact: no round trip through a matrix, so angles that
// need no unwrapping come back bit for bit.
Eigen::Vector3d euler_near(const Eigen::Vector3d& angles, const Eigen::Vector3d& previous);

// sin_cos_degrees reduces angles up to this size exactly (quarter turns times 90 stay exact).
constexpr double kLargestReducedDegrees = 1099511627776.0;  // 2^40

// The Taylor coefficients (1 / n!) sin_cos_degrees and sin_cos_degrees_n sum.
namespace sin_cos_terms {
constexpr double k3 = 1.0 / 6, k5 = 1.0 / 120, k7 = 1.0 / 5040, k9 = 1.0 / 362880, k11 = 1.0 / 39916800,
                 k13 = 1.0 / 6227020800.0, k15 = 1.0 / 1307674368000.0, k17 = 1.0 / 355687428096000.0;
constexpr double k2 = 1.0 / 2, k4 = 1.0 / 24, k6 = 1.0 / 720, k8 = 1.0 / 40320, k10 = 1.0 / 3628800,
                 k12 = 1.0 / 479001600, k14 = 1.0 / 87178291200.0, k16 = 1.0 / 20922789888000.0;
}  // namespace sin_cos_terms

inline void sin_cos_degrees(double degrees, double* sine, double* cosine) {
  if (!(std::abs(degrees) <= kLargestReducedDegrees)) {  // huge, or not a number
    const double r = degrees * (3.14159265358979323846 / 180.0);
    *sine = std::sin(r);
    *cosine = std::cos(r);
    return;
  }
  // The nearest quarter turn (truncating after adding a half: no library call), then the rest in
  // radians: the difference is exact, |r| <= pi / 4.
  const double q = degrees * (1.0 / 90.0);
  const long long turns = static_cast<long long>(q + (q >= 0.0 ? 0.5 : -0.5));
  const double r = (degrees - static_cast<double>(turns) * 90.0) * (3.14159265358979323846 / 180.0);
  // Taylor series to r^17 and r^16 (the next terms are under 1e-19 for |r| <= pi / 4), summed in
  // pairs of powers so the steps do not wait on one another (coefficients: sin_cos_terms).
  using namespace sin_cos_terms;
  const double r2 = r * r, r4 = r2 * r2, r8 = r4 * r4;
  const double s = r * ((1.0 - k3 * r2) + r4 * (k5 - k7 * r2) + r8 * ((k9 - k11 * r2) + r4 * (k13 - k15 * r2) + r8 * k17));
  const double c = (1.0 - k2 * r2) + r4 * (k4 - k6 * r2) + r8 * ((k8 - k10 * r2) + r4 * (k12 - k14 * r2) + r8 * k16);
  // The quadrant, without branches (it changes from one angle to the next): odd quarters swap
  // sine and cosine, and the signs follow the quarter's.
  const double values[2] = {s, c};
  const int odd = static_cast<int>(turns & 1);
  *sine = values[odd] * (1.0 - static_cast<double>(turns & 2));
  *cosine = values[1 - odd] * (1.0 - static_cast<double>((turns + 1) & 2));
}

}  // namespace mostyle
