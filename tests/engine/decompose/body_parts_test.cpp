// Local components and body parts: supports that are one connected piece of the
// skeleton, their regions and plain names, and weights given per body part.
#include "engine/decompose/body_parts.h"

#include <catch2/catch.hpp>
#include <memory>
#include <string>

#include "engine/align/prepare_takes.h"
#include "engine/decompose/decompose_takes.h"
#include "engine/decompose/decomposition.h"
#include "engine/decompose/sparse_coding.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/base/error.h"
#include "engine/prepare/major_skeleton.h"
#include "tests/engine/synthetic_motion.h"
#include "tests/test_data.h"

using namespace mostyle;

namespace {

// The canonical 20-joint skeleton's parents within itself.
std::vector<int> canonical_parents() {
  std::vector<int> majors(kMajorJointCount);
  for (int j = 0; j < kMajorJointCount; ++j) majors[static_cast<size_t>(j)] = j;
  return subset_parents(majors);
}

}  // namespace

TEST_CASE("keep_connected grows one piece from the most energetic joint", "[body_parts]") {
  // A chain 0 - 1 - 2 - 3 and a branch 1 - 4. Energies (per joint): 0: 1, 1: 0, 2: 9, 3: 4, 4: 16.
  const std::vector<int> parents = {-1, 0, 1, 2, 1};
  const std::vector<std::vector<int>> neighbours = neighbours_of(parents);
  Eigen::RowVectorXd row(15);
  row << 1, 0, 0,  0, 0, 0,  3, 0, 0,  0, 2, 0,  0, 0, 4;
  std::vector<char> chosen;
  // Two joints: the centre (4) and its only neighbour (1), although 1 has no energy: the piece
  // stays connected rather than jumping to 2.
  Eigen::RowVectorXd two = row;
  keep_connected(two, 6, neighbours, chosen);
  Eigen::RowVectorXd expected(15);
  expected << 0, 0, 0,  0, 0, 0,  0, 0, 0,  0, 0, 0,  0, 0, 4;
  CHECK(two == expected);  // joint 1 has no energy: the growth stops there
  // Three joints from a row where 1 carries a little: 4, 1, then the best neighbour of {4, 1} (2).
  row(3) = 0.5;
  Eigen::RowVectorXd three = row;
  keep_connected(three, 9, neighbours, chosen);
  expected << 0, 0, 0,  0.5, 0, 0,  3, 0, 0,  0, 0, 0,  0, 0, 4;
  CHECK(three == expected);
}

TEST_CASE("regions, names, parts and connectivity", "[body_parts]") {
  CHECK(body_region_of(static_cast<int>(MajorJoint::kLeftKnee)) == BodyRegion::kLeftLeg);
  CHECK(body_region_of(static_cast<int>(MajorJoint::kRightHand)) == BodyRegion::kRightArm);
  CHECK(body_region_of(static_cast<int>(MajorJoint::kHead)) == BodyRegion::kSpineAndHead);
  CHECK(std::string(body_region_name(BodyRegion::kLeftArm)) == "left arm");
  for (const char* name : {"legs", "arms", "spine", "left-leg", "right-leg", "left-arm", "right-arm"})
    CHECK(body_part_name(parse_body_part(name)) == std::string(name));
  CHECK_THROWS_AS(parse_body_part("tail"), InputError);
  // A side wins over both sides, whatever the order given.
  const std::vector<BodyPart> given = {BodyPart::kLeftLeg, BodyPart::kLegs, BodyPart::kArms};
  CHECK(deciding_part(given, BodyRegion::kLeftLeg) == 0);
  CHECK(deciding_part(given, BodyRegion::kRightLeg) == 1);
  CHECK(deciding_part(given, BodyRegion::kRightArm) == 2);
  CHECK(deciding_part(given, BodyRegion::kSpineAndHead) == -1);
  // Components named by their centre's region, numbered within it.
  std::vector<int> majors(kMajorJointCount);
  for (int j = 0; j < kMajorJointCount; ++j) majors[static_cast<size_t>(j)] = j;
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(3, 3 * kMajorJointCount);
  c(0, 3 * static_cast<int>(MajorJoint::kLeftKnee)) = 2.0;
  c(0, 3 * static_cast<int>(MajorJoint::kLeftAnkle)) = 1.0;
  c(1, 3 * static_cast<int>(MajorJoint::kLeftAnkle) + 1) = 1.0;
  c(2, 3 * static_cast<int>(MajorJoint::kHead) + 2) = 1.0;
  const std::vector<ComponentJoints> parts = describe_components(c, majors);
  REQUIRE(parts.size() == 3);
  CHECK(parts[0].name == "left leg");
  CHECK(parts[1].name == "left leg 2");
  CHECK(parts[2].name == "spine and head");
  CHECK(parts[0].centre == static_cast<int>(MajorJoint::kLeftKnee));
  CHECK(parts[0].columns == std::vector<int>{static_cast<int>(MajorJoint::kLeftKnee), static_cast<int>(MajorJoint::kLeftAnkle)});
  const std::vector<double> w = weights_for_parts({{BodyPart::kLegs, 0.0}, {BodyPart::kSpine, 1.0}}, parts, 0.5);
  CHECK(w == std::vector<double>{0.0, 0.0, 1.0});
  // Connectivity on the canonical tree.
  const std::vector<int> parents = canonical_parents();
  auto col = [](MajorJoint j) { return static_cast<int>(j); };
  CHECK(connected_in({col(MajorJoint::kLeftKnee), col(MajorJoint::kLeftAnkle)}, parents));
  CHECK(connected_in({col(MajorJoint::kHips), col(MajorJoint::kLeftHip), col(MajorJoint::kRightHip)}, parents));
  CHECK_FALSE(connected_in({col(MajorJoint::kLeftKnee), col(MajorJoint::kLeftToe)}, parents));
  CHECK_FALSE(connected_in({col(MajorJoint::kLeftHand), col(MajorJoint::kRightHand)}, parents));
  CHECK_FALSE(connected_in({}, parents));
}

TEST_CASE("local decomposition: every component one connected piece, objective monotone", "[body_parts]") {
  const std::vector<int> parents = canonical_parents();
  const Eigen::MatrixXd x = test::synthetic_motion(240, kMajorJointCount, 5, 0.01, 3);
  for (double sparsity : {0.05, 0.1, 0.2, 0.5}) {
    DecompositionOptions o;
    o.components = 10;
    o.sparsity = sparsity;
    o.locality_parents = parents;
    const Decomposition d = decompose(x, o);
    std::vector<int> majors(kMajorJointCount);
    for (int j = 0; j < kMajorJointCount; ++j) majors[static_cast<size_t>(j)] = j;
    for (const ComponentJoints& c : describe_components(d.components, majors)) {
      INFO("sparsity " << sparsity << ", component " << c.name << " with " << c.columns.size() << " joints");
      CHECK(connected_in(c.columns, parents));
      CHECK(static_cast<int>(c.columns.size()) <= std::max(1, static_cast<int>(std::lround(o.NonzerosPerComponent(60) / 3.0))));
    }
    for (size_t i = 1; i < d.objective_history.size(); ++i)
      CHECK(d.objective_history[i] <= d.objective_history[i - 1] * (1 + 1e-12));
  }
  DecompositionOptions bad;
  bad.locality_parents = {-1, 0};
  CHECK_THROWS_AS(decompose(x, bad), InputError);
}

TEST_CASE("local components on real takes of every convention: connected, and what locality costs",
          "[body_parts]") {
  std::vector<std::string> files = test::asset_motions();
  for (const std::string& f : test::shared_motions()) files.push_back(f);
  for (const std::string& file : files) {
    auto clip = std::make_shared<const Clip>(read_bvh_file(file));
    const auto p = prepare_takes({clip, clip}, {});
    DecompositionOptions o;
    o.components = 10;
    o.sparsity = 0.1;
    const double plain = decompose(p->takes[0].x, o).rmse;
    o.locality_parents = p->parents;
    const Decomposition local = decompose(p->takes[0].x, o);
    INFO(file << ": RMSE " << local.rmse << " local against " << plain << " anywhere (normalized units)");
    for (const ComponentJoints& c : describe_components(local.components, p->majors)) CHECK(connected_in(c.columns, p->parents));
    // What locality costs at k = 10, f = 0.1 (two joints a component): measured 1.08x (Bandai
    // sad) to 1.57x (CMU clumsy) the RMSE of components that take channels anywhere.
    CHECK(local.rmse < 1.75 * plain);
  }
}
