// Units and sizes (engine/kinematics/units.h): the unit names mapped to centimetres, and how tall
// a motion stands whatever it does.
#include <catch2/catch.hpp>

#include "engine/kinematics/units.h"

using namespace mostyle;

TEST_CASE("centimetres_per_unit maps guess_units' names, 0 for an unknown one", "[units]") {
  CHECK(centimetres_per_unit("centimetres") == 1.0);
  CHECK(centimetres_per_unit("metres") == 100.0);
  CHECK(centimetres_per_unit("inches") == Approx(2.54));
  CHECK(centimetres_per_unit("CMU units (1/0.45 inch)") == Approx(5.6444).epsilon(1e-4));
  CHECK(centimetres_per_unit("unknown") == 0.0);
}

TEST_CASE("motion_height measures the motion's tallest frame, not the units", "[units]") {
  Eigen::MatrixXd m(2, 6);
  m << 0, 0, 0, 0, 170, 0,    // a 170-unit standing pose
      50, 10, 0, 50, 100, 0;  // crouched and moved: 90
  CHECK(motion_height(m) == 170.0);
  CHECK(motion_height(m.bottomRows(1)) == 90.0);
  CHECK(motion_height(Eigen::MatrixXd(0, 6)) == 0.0);
}
