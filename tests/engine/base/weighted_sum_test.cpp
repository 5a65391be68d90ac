#include "engine/base/weighted_sum.h"

#include <Eigen/Core>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "tests/engine/synthetic_motion.h"

using namespace mostyle;

TEST_CASE("a weighted sum has the bits of a zeroed vector with each term added in turn", "[weighted_sum]") {
  // Lengths around the vector widths (16 and 4 at a time, and what is left), and from no term
  // to seventeen, with a zero weight, a negative one and -0.0 values among them.
  test::Random random(3);
  for (int length : {0, 1, 3, 4, 5, 15, 16, 17, 20, 63, 64, 67}) {
    for (int count : {0, 1, 2, 8, 17}) {
      const Eigen::MatrixXd x = random.matrix(length, count);
      Eigen::MatrixXd values = x;
      if (length > 2 && count > 0) values(1, 0) = -0.0;
      std::vector<WeightedTerm> terms;
      for (int t = 0; t < count; ++t)
        terms.push_back({t == 1 ? 0.0 : (t % 3 == 2 ? -1.0 : 1.0) * random.uniform(), values.col(t).data()});
      Eigen::VectorXd expected = Eigen::VectorXd::Zero(length);
      for (int t = 0; t < count; ++t) expected += terms[static_cast<size_t>(t)].weight * values.col(t);
      Eigen::VectorXd out = Eigen::VectorXd::Constant(length, 99.0);
      weighted_sum(terms.data(), count, length, out.data());
      CAPTURE(length, count);
      for (int c = 0; c < length; ++c) {
        CAPTURE(c);
        CHECK(out[c] == expected[c]);
        CHECK(std::signbit(out[c]) == std::signbit(expected[c]));
      }
    }
  }
}
