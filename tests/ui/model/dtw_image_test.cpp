// The DTW view's cost picture (ui/model/dtw_image.h) against a hand-worked case and a brute-force
// one: cells at the frames' centres, normalised to the largest.
#include <cmath>

#include <catch2/catch.hpp>

#include "ui/model/dtw_image.h"

using namespace mostyle;
using namespace mostyle::ui;

namespace {

// Two takes whose take 1 was aligned on one-column features a (A's frames) and b (B's).
PreparedTakes aligned(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  PreparedTakes p;
  p.takes.resize(2);
  p.takes[1].alignment.feature.a = a;
  p.takes[1].alignment.feature.b = b;
  return p;
}

}  // namespace

TEST_CASE("dtw image: a few frames, each a cell, by hand") {
  Eigen::MatrixXd a(3, 1), b(2, 1);
  a << 0.0, 1.0, 4.0;
  b << 0.0, 2.0;
  const DtwCostImage img = dtw_cost_image(aligned(a, b));
  REQUIRE(img.rows == 3);
  REQUIRE(img.cols == 2);
  CHECK(img.frames_a == 3);
  CHECK(img.frames_b == 2);
  // |a_i - b_j|: 0 2 / 1 1 / 4 2, over the largest (4).
  const float expected[3][2] = {{0.0f, 0.5f}, {0.25f, 0.25f}, {1.0f, 0.5f}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 2; ++c) CHECK(img.cost(r, c) == Approx(expected[r][c]));
}

TEST_CASE("dtw image: long takes are sampled at cell centres, no more than kMaxCells each way") {
  const int fa = 300, fb = 130;
  Eigen::MatrixXd a(fa, 2), b(fb, 2);
  for (int i = 0; i < fa; ++i) a.row(i) << std::sin(0.05 * i), std::cos(0.03 * i);
  for (int j = 0; j < fb; ++j) b.row(j) << std::sin(0.07 * j), 0.5 * j / fb;
  const DtwCostImage img = dtw_cost_image(aligned(a, b));
  REQUIRE(img.rows == DtwCostImage::kMaxCells);
  REQUIRE(img.cols == DtwCostImage::kMaxCells);
  // Brute force: each cell's centre frame, its distance, then the largest.
  Eigen::MatrixXf brute(img.rows, img.cols);
  for (int r = 0; r < img.rows; ++r)
    for (int c = 0; c < img.cols; ++c) {
      const int i = static_cast<int>(std::floor((r + 0.5) * fa / img.rows));
      const int j = static_cast<int>(std::floor((c + 0.5) * fb / img.cols));
      brute(r, c) = static_cast<float>((a.row(i) - b.row(j)).norm());
    }
  brute /= brute.maxCoeff();
  CHECK((img.cost - brute).cwiseAbs().maxCoeff() < 1e-6f);
  CHECK(img.cost.maxCoeff() == 1.0f);
}

TEST_CASE("dtw image: one take, or no features, gives no cells") {
  PreparedTakes one;
  one.takes.resize(1);
  CHECK(dtw_cost_image(one).rows == 0);
  CHECK(dtw_cost_image(aligned(Eigen::MatrixXd(), Eigen::MatrixXd(2, 1))).cols == 0);
}
