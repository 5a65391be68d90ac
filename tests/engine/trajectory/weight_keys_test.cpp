// Weights keyed in time (engine/trajectory/weight_keys.h): eased between keys (smoothstep) worked by
// hand, held outside them, per frame as at each time, every bad key refused in a sentence; and
// the keyed clock (trajectory/mixed_clock.h) the same as the constant one when every key is the same.
#include "engine/trajectory/weight_keys.h"

#include <catch2/catch.hpp>

#include "engine/trajectory/mixed_clock.h"
#include "engine/base/error.h"

using namespace mostyle;

TEST_CASE("weight keys: eased between keys, held outside them, worked by hand") {
  const WeightKeys keys{{2.0, {1.0, 0.0}}, {6.0, {0.0, 1.0}}, {8.0, {0.5, 0.5}}};
  std::vector<double> w;
  weights_at(keys, 0.0, w);
  CHECK(w == std::vector<double>{1.0, 0.0});  // before the first: held
  weights_at(keys, 2.0, w);
  CHECK(w == std::vector<double>{1.0, 0.0});
  weights_at(keys, 4.0, w);  // half way: smoothstep(1/2) = 1/2
  CHECK(w[0] == Approx(0.5));
  CHECK(w[1] == Approx(0.5));
  weights_at(keys, 3.0, w);  // a quarter: 3 (1/4)^2 - 2 (1/4)^3 = 5/32
  CHECK(w[1] == Approx(5.0 / 32.0));
  CHECK(w[0] + w[1] == Approx(1.0));
  weights_at(keys, 6.0, w);
  CHECK(w == std::vector<double>{0.0, 1.0});
  weights_at(keys, 7.0, w);
  CHECK(w[0] == Approx(0.25));
  weights_at(keys, 100.0, w);
  CHECK(w == std::vector<double>{0.5, 0.5});  // after the last: held
  // Per frame, as at each frame's time.
  Eigen::MatrixXd frames;
  weights_over_frames(keys, 301, 30.0, frames);
  REQUIRE(frames.rows() == 301);
  for (Eigen::Index f = 0; f < frames.rows(); f += 7) {
    weights_at(keys, f / 30.0, w);
    CHECK(frames(f, 0) == Approx(w[0]).margin(1e-15));
    CHECK(frames(f, 1) == Approx(w[1]).margin(1e-15));
  }
  // No kink at a key: the change over one frame on either side of it is tiny.
  weights_over_frames(keys, 301, 30.0, frames);
  CHECK(std::abs(frames(181, 1) - frames(180, 1)) < 0.01);
  CHECK(std::abs(frames(180, 1) - frames(179, 1)) < 0.01);
}

TEST_CASE("weight keys: bad keys are refused in one sentence naming the key") {
  CHECK_NOTHROW(validate_keys({}, 2));
  CHECK_THROWS_WITH(validate_keys({{1.0, {0.5, 0.5}}, {1.0, {1.0, 0.0}}}, 2),
                    "expected keys in order of time: key 2 (at 1 s) does not come after key 1 (at 1 s)");
  CHECK_THROWS_WITH(validate_keys({{-1.0, {0.5, 0.5}}}, 2), Catch::Contains("key 1's time in seconds from 0 up"));
  CHECK_THROWS_WITH(validate_keys({{0.0, {0.5, 0.5}}, {2.0, {1.0}}}, 2),
                    "expected 2 weights, one per take, in key 2 (at 2 s), found 1");
  CHECK_THROWS_AS(validate_keys({{std::nan(""), {0.5, 0.5}}}, 2), InputError);
}

TEST_CASE("weight keys: the keyed clock with one set of weights is the constant clock") {
  // Two takes: the reference and one running 1.5 times as fast over the middle.
  CommonTimeline t;
  const int u = 60;
  t.frames = {Eigen::VectorXd::LinSpaced(u, 0, u - 1), Eigen::VectorXd(u)};
  double b = 0;
  for (int k = 0; k < u; ++k) {
    t.frames[1][k] = b;
    b += k > 20 && k < 40 ? 1.5 : 1.0;
  }
  t.first = {0, 0};
  t.last = {u - 1, u - 1};
  Eigen::VectorXd constant, keyed;
  mixed_timeline(t, std::vector<double>{0.3, 0.7}, {0, u - 1}, constant);
  Eigen::MatrixXd sample_w;
  mixed_timeline(t, WeightKeys{{0.0, {0.3, 0.7}}, {1.0, {0.3, 0.7}}}, 30.0, {0, u - 1}, keyed, &sample_w);
  REQUIRE(keyed.size() == constant.size());
  CHECK((keyed - constant).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(sample_w.rows() == u);
  CHECK(sample_w(10, 1) == 0.7);
  // Keyed from the reference's timing to the other's: the first samples advance as the reference,
  // the last as the other take (1.5 frames a sample over its fast middle is over by then).
  mixed_timeline(t, WeightKeys{{0.0, {1.0, 0.0}}, {0.5, {0.0, 1.0}}}, 30.0, {0, u - 1}, keyed, &sample_w);
  CHECK(sample_w(0, 0) == 1.0);
  CHECK(sample_w(u - 1, 1) == 1.0);
  CHECK(keyed[1] - keyed[0] == Approx(1.0));
  CHECK_THROWS_AS(mixed_timeline(t, WeightKeys{}, 30.0, {0, u - 1}, keyed), InputError);
  CHECK_THROWS_AS(mixed_timeline(t, WeightKeys{{0.0, {1.0}}}, 30.0, {0, u - 1}, keyed), InputError);
}
