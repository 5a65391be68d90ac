#include "engine/measure/foot_contact.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "engine/base/error.h"
#include "tests/engine/synthetic_gait.h"
#include "tests/engine/two_leg_walk.h"

using namespace mostyle;
using namespace mostyle::test;

namespace {

constexpr double kExact = 1e-9;   // file units (cm here): IK and locks hold to rounding

}  // namespace

TEST_CASE("contacts of a synthetic walk are its planted phases", "[foot_contact]") {
  const FootRig rig = test_rig();
  Eigen::MatrixXd planted;
  const Eigen::MatrixXd w = walk(150, 0.0, &planted);
  const Eigen::MatrixXd c = detect_foot_contacts(w, rig);
  REQUIRE(c.rows() == 150);
  REQUIRE(c.cols() == 2);
  // Each frame agrees, but for at most one frame at either end of a contact.
  for (int side = 0; side < 2; ++side) {
    for (int f = 1; f + 1 < 150; ++f) {
      INFO("side " << side << " frame " << f);
      if (planted(f - 1, side) == planted(f, side) && planted(f + 1, side) == planted(f, side))
        CHECK(c(f, side) == planted(f, side));
    }
  }
  CHECK(stance_speed(w, c, rig) < kExact);
  // A foot skating at 20 cm/s (under the speed threshold) is still in contact.
  Eigen::MatrixXd skating_stance;
  const Eigen::MatrixXd skating = walk(150, 20.0, &skating_stance);
  CHECK(detect_foot_contacts(skating, rig).sum() > 0.8 * skating_stance.sum());
}

TEST_CASE("contacts are tidied as detection tidies them: short breaks filled, short contacts dropped",
          "[foot_contact]") {
  FootRig rig = test_rig();  // 30 fps: breaks of up to 2 frames filled, contacts under 3 frames dropped
  rig.options.min_contact_seconds = 0.1;
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(20, 2);
  c.col(0).segment(2, 5).setOnes();   // 2-6
  c.col(0).segment(8, 6).setOnes();   // 8-13: a break of one frame (7)
  c.col(1).segment(4, 2).setOnes();   // 4-5: too short
  c.col(1).segment(10, 4).setOnes();  // 10-13
  tidy_contacts(c, rig);
  CHECK(c.col(0).segment(2, 12).minCoeff() == 1.0);
  CHECK(c(1, 0) == 0.0);
  CHECK(c(14, 0) == 0.0);
  CHECK(c.col(1).segment(0, 10).maxCoeff() == 0.0);
  CHECK(c.col(1).segment(10, 4).minCoeff() == 1.0);
}

TEST_CASE("tidying keeps contacts cut by the take's ends and rounds the shortest contact to a frame",
          "[foot_contact]") {
  FootRig rig = test_rig();
  rig.options.min_contact_seconds = 0.1;  // 3 frames at 30 fps
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(20, 2);
  c.col(0).head(2).setOnes();   // 0-1: cut by the start
  c.col(0).tail(1).setOnes();   // 19: cut by the end (a landing)
  c.col(1).segment(5, 2).setOnes();  // 5-6: short, inside
  tidy_contacts(c, rig);
  CHECK(c.col(0).head(2).minCoeff() == 1.0);
  CHECK(c(19, 0) == 1.0);
  CHECK(c.col(1).maxCoeff() == 0.0);
  rig.fps = 24.0;  // 0.1 s is 2.4 frames: 2 are enough
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(20, 2);
  d.col(0).segment(5, 2).setOnes();
  d.col(1).segment(9, 1).setOnes();
  tidy_contacts(d, rig);
  CHECK(d.col(0).segment(5, 2).minCoeff() == 1.0);
  CHECK(d.col(1).maxCoeff() == 0.0);
}

namespace {

// 1 where a synthetic gait's foot is planted (test::gait_take), per frame. F x 2.
Eigen::MatrixXd gait_planted(const test::GaitSpec& g, int frames) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(frames, 2);
  for (int f = 0; f < frames; ++f)
    for (int side = 0; side < 2; ++side) {
      const double phase = f / g.fps / g.cycle_s + g.start + (side == 0 || g.together ? 0.0 : 0.5);
      out(f, side) = phase - std::floor(phase) < g.stance ? 1.0 : 0.0;
    }
  return out;
}

// Frames where detected contacts differ from the planted phases, leaving out those within
// `slack` frames of a change of either.
int contact_errors(const Eigen::MatrixXd& detected, const Eigen::MatrixXd& planted, int slack) {
  int errors = 0;
  for (int side = 0; side < 2; ++side)
    for (Eigen::Index f = 0; f < planted.rows(); ++f) {
      bool near_change = false;
      for (Eigen::Index u = std::max<Eigen::Index>(1, f - slack); u <= std::min(planted.rows() - 1, f + slack); ++u)
        near_change = near_change || planted(u, side) != planted(u - 1, side);
      if (!near_change && detected(f, side) != planted(f, side)) ++errors;
    }
  return errors;
}

}  // namespace

TEST_CASE("contacts of a walk in place: the planted foot moves with the belt under still hips", "[foot_contact]") {
  test::GaitSpec g;
  g.in_place = true;
  g.start = 0.3;
  const int frames = 150;
  const Eigen::MatrixXd c = detect_foot_contacts(test::gait_take(g, frames), test::gait_rig(g.fps));
  const Eigen::MatrixXd planted = gait_planted(g, frames);
  CHECK(contact_errors(c, planted, 1) == 0);
  // The same walk travelling is detected the same way (its planted foot is still).
  g.in_place = false;
  CHECK(contact_errors(detect_foot_contacts(test::gait_take(g, frames), test::gait_rig(g.fps)), planted, 1) == 0);
  // A run in place: short contacts, flight phases between them; at 24 fps too.
  for (const double fps : {24.0, 120.0}) {
    test::GaitSpec run;
    run.in_place = true;
    run.fps = fps;
    run.cycle_s = 0.7;
    run.stance = 0.3;
    run.stride = 0.6;
    run.lift = 0.3;
    const int n = static_cast<int>(2.0 * fps);
    INFO(fps << " fps");
    const Eigen::MatrixXd rc = detect_foot_contacts(test::gait_take(run, n), test::gait_rig(fps));
    CHECK(contact_errors(rc, gait_planted(run, n), fps > 100 ? 3 : 1) == 0);
    CHECK(rc.col(0).sum() > 0.5 * gait_planted(run, n).col(0).sum());
  }
}

TEST_CASE("contacts of a loop clip run across its end", "[foot_contact]") {
  test::GaitSpec g;  // one cycle in place, cut while the left foot stands
  g.in_place = true;
  g.start = 0.3;
  const int n = 30;
  const Eigen::MatrixXd world = test::gait_take(g, n);  // frame n would be frame 0 again
  const Eigen::MatrixXd c = detect_foot_contacts(world, test::gait_rig(g.fps), n);
  const Eigen::MatrixXd planted = gait_planted(g, n);
  CHECK(c(0, 0) == 1.0);  // the stance across the end is one contact: both ends of it kept
  CHECK(c(n - 1, 0) == 1.0);
  Eigen::MatrixXd wrapped(n + 2, 2);  // the loop's contacts around its end, to check the changes there
  wrapped << planted.bottomRows(1), planted, planted.topRows(1);
  Eigen::MatrixXd detected(n + 2, 2);
  detected << c.bottomRows(1), c, c.topRows(1);
  CHECK(contact_errors(detected, wrapped, 1) == 0);
  // A loop whose last frame repeats its first: that frame's contacts are frame 0's.
  const Eigen::MatrixXd r = detect_foot_contacts(test::gait_take(g, n + 1), test::gait_rig(g.fps), n);
  CHECK(r.row(n) == r.row(0));
  CHECK(r.topRows(n) == c);
  CHECK_THROWS_AS(detect_foot_contacts(world, test::gait_rig(g.fps), n + 1), InputError);
  CHECK_THROWS_AS(detect_foot_contacts(world, test::gait_rig(g.fps), 1), InputError);
}

TEST_CASE("contacts follow a floor that rises over the take, and a landing in its last frames", "[foot_contact]") {
  test::GaitSpec g;
  const int frames = 240;  // 8 s, the ground rising 0.3 m (a third of the leg)
  Eigen::MatrixXd world = test::gait_take(g, frames);
  for (Eigen::Index f = 0; f < frames; ++f)
    for (Eigen::Index j = 0; j < 9; ++j) world(f, 3 * j + 1) += 0.3 * f / (frames - 1);
  const Eigen::MatrixXd c = detect_foot_contacts(world, test::gait_rig(g.fps));
  CHECK(contact_errors(c, gait_planted(g, frames), 1) == 0);
  // Cut two frames after the left foot touches down (the ankle still slowing): it has landed.
  test::GaitSpec landing;
  landing.start = 0.5;  // the left foot lands at frame 15
  const int n = 15 + 3;
  const Eigen::MatrixXd end = detect_foot_contacts(test::gait_take(landing, n), test::gait_rig(landing.fps));
  CHECK(end(n - 1, 0) == 1.0);
  CHECK(end(n - 4, 0) == 0.0);
}

TEST_CASE("contacts are carried through a warp", "[foot_contact]") {
  Eigen::MatrixXd b(5, 2);
  b << 1, 0, 1, 0, 0, 1, 0, 1, 1, 1;
  Eigen::VectorXd warp(4);
  warp << 0.0, 1.6, 2.4, 4.0;  // rounds to B frames 0, 2, 2, 4
  const Eigen::MatrixXd carried = carry_contacts(b, warp);
  Eigen::MatrixXd expected(4, 2);
  expected << 1, 0, 0, 1, 0, 1, 1, 1;
  CHECK(carried == expected);
}

TEST_CASE("foot contact options and shapes are checked", "[foot_contact]") {
  FootContactOptions o;
  CHECK_NOTHROW(o.Validate());
  o.speed_fraction = -1;
  CHECK_THROWS_AS(o.Validate(), InputError);
  o = FootContactOptions{};
  o.blend_seconds = NAN;
  CHECK_THROWS_AS(o.Validate(), InputError);
  const std::vector<int> majors = {0, 12, 13, 14, 16, 17, 18};
  CHECK_THROWS_AS(make_foot_rig(majors, std::vector<double>(7, 1.0), 0.0), InputError);
  CHECK_THROWS_AS(make_foot_rig(majors, std::vector<double>(6, 1.0), 30.0), InputError);
  const FootRig rig = make_foot_rig(majors, {0, 5, 40, 40, 5, 42, 38}, 30.0);
  CHECK(rig.legs[0].hip == 1);
  CHECK(rig.legs[0].ankle == 3);
  CHECK(rig.legs[0].toe == -1);
  CHECK(rig.legs[1].knee == 5);
  CHECK(rig.leg_length == Approx(80.0));
  CHECK(rig.body_height == Approx(80.0));  // the legs only: this skeleton has no trunk

  const FootRig test = test_rig();
  const Eigen::MatrixXd too_narrow = Eigen::MatrixXd::Zero(10, 12);
  CHECK_THROWS_AS(detect_foot_contacts(too_narrow, test), InputError);
  CHECK_THROWS_AS(carry_contacts(Eigen::MatrixXd::Zero(0, 2), Eigen::VectorXd::Zero(3)), InputError);
  // No frames: no contacts, no sliding, nothing to lock.
  const Eigen::MatrixXd empty(0, 24);
  CHECK(detect_foot_contacts(empty, test).rows() == 0);
}

TEST_CASE("foot contacts: foot strikes are landings, worked by hand", "[foot_contact]") {
  Eigen::MatrixXd c(8, 2);
  c << 1, 0,  //
      1, 0,   //
      0, 1,   // right lands at 2
      0, 1,   //
      1, 0,   // left lands at 4
      1, 1,   // right lands at 5
      0, 0,   //
      1, 1;   // both land at 7
  CHECK(foot_strikes(c, 0) == std::vector<int>{4, 7});  // frame 0 planted is not a strike
  CHECK(foot_strikes(c, 1) == std::vector<int>{2, 5, 7});
}
