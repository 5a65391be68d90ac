#include "engine/kinematics/euler.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

using namespace mostyle;

namespace {

constexpr double kMatrixTolerance = 1e-12;  // round trips through sin/cos/atan2
constexpr EulerOrder kOrders[] = {EulerOrder::kXYZ, EulerOrder::kXZY, EulerOrder::kYXZ,
                                  EulerOrder::kYZX, EulerOrder::kZXY, EulerOrder::kZYX};

double angle_distance(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 360.0);
  return std::min(d, 360.0 - d);
}

}  // namespace

TEST_CASE("order names, axes and parsing", "[euler]") {
  const char* names[] = {"XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX"};
  for (int i = 0; i < 6; ++i) {
    CHECK(euler_order_name(kOrders[i]) == names[i]);
    EulerOrder parsed;
    REQUIRE(parse_euler_order(names[i], &parsed));
    CHECK(parsed == kOrders[i]);
  }
  EulerOrder o;
  CHECK(parse_euler_order("zxy", &o));
  CHECK(o == EulerOrder::kZXY);
  CHECK(euler_axes(EulerOrder::kZXY) == std::array<int, 3>{2, 0, 1});
  CHECK_FALSE(parse_euler_order("XYX", &o));
  CHECK_FALSE(parse_euler_order("XY", &o));
  CHECK_FALSE(parse_euler_order("", &o));
}

TEST_CASE("axis rotations are right-handed, in degrees", "[euler]") {
  // Rx(90) takes +Y to +Z, Ry(90) takes +Z to +X, Rz(90) takes +X to +Y.
  CHECK((axis_rotation(0, 90) * Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitZ()).norm() < 1e-15);
  CHECK((axis_rotation(1, 90) * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitX()).norm() < 1e-15);
  CHECK((axis_rotation(2, 90) * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm() < 1e-15);
  // The same as Eigen's angle-axis.
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Matrix3d expected =
        Eigen::AngleAxisd(0.3, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
    CHECK((axis_rotation(axis, 0.3 * 180 / M_PI) - expected).norm() < 1e-15);
  }
}

TEST_CASE("euler_to_matrix multiplies in channel order", "[euler]") {
  const Eigen::Vector3d angles(10, -20, 30);
  // ZXY: Rz(10) * Rx(-20) * Ry(30).
  const Eigen::Matrix3d expected = axis_rotation(2, 10) * axis_rotation(0, -20) * axis_rotation(1, 30);
  CHECK((euler_to_matrix(EulerOrder::kZXY, angles) - expected).norm() < 1e-15);
}

TEST_CASE("matrix_to_euler round trip for random angles in all orders", "[euler]") {
  std::mt19937 rng(1234);
  std::uniform_real_distribution<double> outer(-180, 180), middle(-89.9, 89.9);
  for (EulerOrder order : kOrders) {
    INFO(euler_order_name(order));
    for (int trial = 0; trial < 2000; ++trial) {
      const Eigen::Vector3d angles(outer(rng), middle(rng), outer(rng));
      const Eigen::Matrix3d r = euler_to_matrix(order, angles);
      const Eigen::Vector3d back = matrix_to_euler(order, r);
      // The principal solution is the input itself: middle in (-90, 90), outer in [-180, 180].
      CHECK(angle_distance(back[0], angles[0]) < 1e-9);
      CHECK(back[1] == Approx(angles[1]).margin(1e-9));
      CHECK(angle_distance(back[2], angles[2]) < 1e-9);
      CHECK(std::abs(back[1]) <= 90.0);
      CHECK(std::abs(back[0]) <= 180.0);
      CHECK(std::abs(back[2]) <= 180.0);
      CHECK((euler_to_matrix(order, back) - r).norm() < kMatrixTolerance);
    }
  }
}

TEST_CASE("matrix_to_euler at and near gimbal lock", "[euler]") {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> outer(-180, 180);
  for (EulerOrder order : kOrders) {
    INFO(euler_order_name(order));
    for (double middle : {90.0, -90.0, 89.999999, -89.9999999, 90 - 1e-12}) {
      for (int trial = 0; trial < 200; ++trial) {
        const Eigen::Vector3d angles(outer(rng), middle, outer(rng));
        const Eigen::Matrix3d r = euler_to_matrix(order, angles);
        const Eigen::Vector3d back = matrix_to_euler(order, r);
        // Only the matrix is determined at the lock; it must come back.
        CHECK((euler_to_matrix(order, back) - r).norm() < 1e-9);
        CHECK(back[1] == Approx(middle).margin(1e-6));
      }
    }
    // Exactly at the lock the third angle is 0 and the first carries the rest.
    const Eigen::Matrix3d locked = euler_to_matrix(order, Eigen::Vector3d(30, 90, 20));
    const Eigen::Vector3d back = matrix_to_euler(order, locked);
    CHECK(back[2] == 0.0);
    CHECK((euler_to_matrix(order, back) - locked).norm() < kMatrixTolerance);
  }
}

TEST_CASE("matrix_to_euler_near picks the nearest equivalent angles", "[euler]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> any(-720, 720), small(-20, 20);
  for (EulerOrder order : kOrders) {
    INFO(euler_order_name(order));
    for (int trial = 0; trial < 1000; ++trial) {
      const Eigen::Vector3d previous(any(rng), any(rng), any(rng));
      const Eigen::Vector3d target = previous + Eigen::Vector3d(small(rng), small(rng), small(rng));
      const Eigen::Matrix3d r = euler_to_matrix(order, target);
      const Eigen::Vector3d near = matrix_to_euler_near(order, r, previous);
      CHECK((euler_to_matrix(order, near) - r).norm() < 1e-9);
      // Brute force over both solutions and shifts of -2..2 turns: none is closer.
      const Eigen::Vector3d first = matrix_to_euler(order, r);
      const Eigen::Vector3d second(first[0] + 180, 180 - first[1], first[2] + 180);
      double best = INFINITY;
      for (const Eigen::Vector3d& base : {first, second}) {
        for (int a = -3; a <= 3; ++a)
          for (int b = -3; b <= 3; ++b)
            for (int c = -3; c <= 3; ++c) {
              const Eigen::Vector3d candidate = base + 360.0 * Eigen::Vector3d(a, b, c);
              best = std::min(best, (candidate - previous).norm());
            }
      }
      CHECK((near - previous).norm() <= best + 1e-9);
      // Each angle within 180 of the previous one: no jumps.
      CHECK((near - previous).cwiseAbs().maxCoeff() <= 180.0 + 1e-9);
    }
  }
}

TEST_CASE("matrix_to_euler_near through gimbal lock keeps the third angle", "[euler]") {
  for (EulerOrder order : kOrders) {
    INFO(euler_order_name(order));
    const Eigen::Vector3d previous(40, 89, -35);
    const Eigen::Matrix3d locked = euler_to_matrix(order, Eigen::Vector3d(41, 90, -35));
    const Eigen::Vector3d near = matrix_to_euler_near(order, locked, previous);
    CHECK((euler_to_matrix(order, near) - locked).norm() < kMatrixTolerance);
    // The principal answer would put the third angle at 0 and the first far away.
    CHECK(near[2] == -35.0);
    CHECK(near[0] == Approx(41).margin(1e-9));
  }
}

TEST_CASE("euler_near is exact and picks the nearest equivalent", "[euler]") {
  const Eigen::Vector3d angles(10.123456789, 20.5, -30.25);
  // Nothing to unwrap: the same bits.
  CHECK(euler_near(angles, Eigen::Vector3d(12, 19, -29)) == angles);
  // A wrap: 179 -> -179 continues as 181.
  const Eigen::Vector3d wrapped = euler_near(Eigen::Vector3d(-179, 0, 0), Eigen::Vector3d(179, 0, 0));
  CHECK(wrapped == Eigen::Vector3d(181, 0, 0));
  // The other solution when it is closer: (a+180, 180-b, c+180) of (0, 80, 0) near (180, 100, 180).
  const Eigen::Vector3d other = euler_near(Eigen::Vector3d(0, 80, 0), Eigen::Vector3d(180, 100, 180));
  CHECK(other == Eigen::Vector3d(180, 100, 180));
  for (EulerOrder order : kOrders) {
    CHECK((euler_to_matrix(order, other) - euler_to_matrix(order, Eigen::Vector3d(0, 80, 0))).norm() <
          kMatrixTolerance);
  }
}

TEST_CASE("sines and cosines of degrees: to the last digits, exact at quarter turns", "[euler]") {
  double worst = 0.0;
  for (int k = -200000; k <= 200000; ++k) {
    const double degrees = k * 0.0123456789 + (k % 7) * 1e-9;  // -2469 to 2469 degrees, uneven
    double s, c;
    sin_cos_degrees(degrees, &s, &c);
    const long double r = static_cast<long double>(degrees) * 3.14159265358979323846264338327950288L / 180.0L;
    worst = std::max({worst, static_cast<double>(std::fabs(s - std::sin(r))), static_cast<double>(std::fabs(c - std::cos(r)))});
  }
  CHECK(worst < 4e-16);
  for (int quarter = -8; quarter <= 8; ++quarter) {
    double s, c;
    sin_cos_degrees(90.0 * quarter, &s, &c);
    const int q = ((quarter % 4) + 4) % 4;
    CHECK(s == (q == 1 ? 1.0 : q == 3 ? -1.0 : 0.0));
    CHECK(c == (q == 0 ? 1.0 : q == 2 ? -1.0 : 0.0));
  }
  double s, c;
  sin_cos_degrees(std::nan(""), &s, &c);
  CHECK(std::isnan(s));
  CHECK(std::isnan(c));
  sin_cos_degrees(1e300, &s, &c);  // beyond exact reduction: as the library computes it
  CHECK(s == std::sin(1e300 * (M_PI / 180.0)));
  CHECK(std::abs(axis_rotation(2, 30.0)(1, 0) - 0.5) < 1e-16);
}

TEST_CASE("sines and cosines of many angles at once: the same values bit for bit as one at a time", "[euler]") {
  // Every kind of angle sin_cos_degrees meets, in groups of four and not: quarter turns of both
  // signs (and -0, which BVH files write as -0.000000), halves between quarters, huge angles and
  // NaN (one at a time inside a group), and ordinary ones.
  std::vector<double> degrees = {0.0, -0.0, 45.0, -45.0, 90.0, -90.0, 135.0, -225.0, 180.0, -180.0, 270.0,
                                 -270.0, 360.0, -360.0, 1e12, -1e12, std::nan(""), INFINITY, -INFINITY, 1e9,
                                 -1e9, 44.99999999, -135.0000001, 89.5, -0.5, 1099511627776.0, -1099511627777.0};
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> any(-1000.0, 1000.0);
  for (int k = 0; k < 4001; ++k) degrees.push_back(any(random));
  for (size_t n : {degrees.size(), size_t{0}, size_t{1}, size_t{3}, size_t{5}}) {
    std::vector<double> s(n), c(n);
    sin_cos_degrees_n(degrees.data(), n, s.data(), c.data());
    for (size_t k = 0; k < n; ++k) {
      double one_s, one_c;
      sin_cos_degrees(degrees[k], &one_s, &one_c);
      INFO("angle " << degrees[k]);
      if (std::isnan(one_s)) {
        CHECK(std::isnan(s[k]));
        CHECK(std::isnan(c[k]));
        continue;
      }
      CHECK(std::memcmp(&s[k], &one_s, sizeof(double)) == 0);  // -0 and +0 told apart
      CHECK(std::memcmp(&c[k], &one_c, sizeof(double)) == 0);
    }
  }
}
