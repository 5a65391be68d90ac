#pragma once
// Euler angles in the six Tait-Bryan orders BVH files use, in degrees.
#include <Eigen/Core>
#include <array>
#include <string>
#include <string_view>

namespace mostyle {

// Named as the channels appear: kZXY is "Zrotation Xrotation Yrotation", R = Rz * Rx * Ry.
enum class EulerOrder { kXYZ, kXZY, kYXZ, kYZX, kZXY, kZYX };

std::array<int, 3> euler_axes(EulerOrder order);  // axis indices 0..2 in channel order
std::string euler_order_name(EulerOrder order);   // "ZXY"
bool parse_euler_order(std::string_view text, EulerOrder* order);  // "zxy" too; false if not one

// Rotation about axis 0, 1 or 2 by `degrees` (right-handed).
Eigen::Matrix3d axis_rotation(int axis, double degrees);

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

}  // namespace mostyle
