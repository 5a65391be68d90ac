#include "engine/kinematics/sample_rows.h"

#include <catch2/catch.hpp>

#include "engine/base/error.h"

using namespace mostyle;

namespace {
constexpr double kExact = 1e-9;  // linear interpolation of integers, rounding only
}  // namespace

TEST_CASE("sample_rows interpolates linearly and clamps", "[sample_rows]") {
  Eigen::MatrixXd x(3, 2);
  x << 0, 10,  //
      2, 20,   //
      6, 40;
  Eigen::VectorXd t(7);
  t << -1.0, 0.0, 0.25, 1.0, 1.5, 2.0, 5.0;
  Eigen::MatrixXd expected(7, 2);
  expected << 0, 10,  // clamped to the first row
      0, 10,          //
      0.5, 12.5,      //
      2, 20,          //
      4, 30,          //
      6, 40,          //
      6, 40;          // clamped to the last row
  const Eigen::MatrixXd out = sample_rows(x, t);
  REQUIRE(out.rows() == 7);
  REQUIRE(out.cols() == 2);
  CHECK((out - expected).cwiseAbs().maxCoeff() < kExact);
  // Into a buffer of the right size, and from a single row.
  Eigen::MatrixXd buffer(7, 2);
  const double* data = buffer.data();
  sample_rows(x, t, buffer);
  CHECK(buffer.data() == data);
  CHECK(buffer == out);
  const Eigen::MatrixXd one = sample_rows(x.topRows(1), t);
  for (Eigen::Index k = 0; k < t.size(); ++k) CHECK(one.row(k) == x.row(0));
  CHECK_THROWS_AS(sample_rows(Eigen::MatrixXd(0, 2), t), InputError);
}
