#include "tests/engine/worker/blend_at.h"
#include "engine/export/export_solve.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "engine/io/bvh/bvh_read.h"
#include "engine/io/bvh/bvh_write.h"
#include "engine/kinematics/convert.h"
#include "engine/base/error.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/resample.h"
#include "engine/kinematics/units.h"
#include "tests/engine/synthetic_motion.h"
#include "tests/test_data.h"

using namespace mostyle;
using mostyle::test::Random;

namespace {

// Reachable targets come back to rounding; relative to the skeleton's height.
constexpr double kExactFit = 1e-9;
// Acceptance bounds: exported major joints vs the blend, relative to the height.
constexpr double kMaxFit = 0.01;
constexpr double kMeanFit = 0.002;
constexpr double kMaxEulerStep = 180.0;  // degrees between frames after unwrapping

void add_joint(Skeleton& s, const std::string& name, int parent, const Eigen::Vector3d& offset,
               const std::vector<Channel>& channels) {
  Joint j;
  j.name = name;
  j.parent = parent;
  j.offset = offset;
  j.channels = channels;
  j.first_channel = s.channel_count;
  s.channel_count += static_cast<int>(channels.size());
  s.joints.push_back(j);
}

void add_end_site(Skeleton& s, int parent, const Eigen::Vector3d& offset) {
  Joint j;
  j.name = s.joints[parent].name + " End Site";
  j.parent = parent;
  j.offset = offset;
  j.end_site = true;
  j.first_channel = s.channel_count;
  s.joints.push_back(j);
}

const std::vector<Channel> kPositions = {Channel::kXposition, Channel::kYposition, Channel::kZposition};
const std::vector<Channel> kZxy = {Channel::kZrotation, Channel::kXrotation, Channel::kYrotation};
const std::vector<Channel> kZyx = {Channel::kZrotation, Channel::kYrotation, Channel::kXrotation};
const std::vector<Channel> kXyz = {Channel::kXrotation, Channel::kYrotation, Channel::kZrotation};

std::vector<Channel> concat(std::vector<Channel> a, const std::vector<Channel>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// A Bandai-like test skeleton: a still ROOT dummy with six channels, the trajectory on its child
// Hips (position channels replace the OFFSET), a rigid pelvis with three children, a chest with a
// neck and two clavicles (joints that are not major), fingers, End Sites, mixed Euler orders.
struct TestRig {
  Skeleton skeleton;
  std::vector<int> majors;  // joints playing the major roles (targets)
  int root = 0, hips = 1, finger = -1;
};

TestRig make_rig() {
  TestRig r;
  Skeleton& s = r.skeleton;
  add_joint(s, "Root", -1, {0, 0, 0}, concat(kPositions, kZxy));           // 0
  add_joint(s, "Hips", 0, {0, 90, 0}, concat(kPositions, kZxy));           // 1
  add_joint(s, "Spine", 1, {0, 10, 1}, kZyx);                               // 2
  add_joint(s, "Chest", 2, {0, 12, 0}, kZyx);                               // 3
  add_joint(s, "Neck", 3, {0, 10, 0}, kXyz);                                // 4
  add_joint(s, "Head", 4, {0, 8, 1}, kZyx);                                 // 5
  add_end_site(s, 5, {0, 6, 0});                                            // 6
  for (int side = 0; side < 2; ++side) {
    const double x = side == 0 ? 1.0 : -1.0;
    const std::string p = side == 0 ? "L" : "R";
    const int clavicle = static_cast<int>(s.joints.size());
    add_joint(s, p + "Clavicle", 3, {4 * x, 8, 0}, kZyx);
    add_joint(s, p + "Arm", clavicle, {8 * x, 0, 0}, kZyx);
    add_joint(s, p + "ForeArm", clavicle + 1, {25 * x, 0, 0}, kXyz);
    add_joint(s, p + "Hand", clavicle + 2, {22 * x, 0, 0}, kZyx);
    add_joint(s, p + "Finger", clavicle + 3, {4 * x, 0, 1}, kZyx);
    add_end_site(s, clavicle + 4, {3 * x, 0, 0});
    if (side == 0) r.finger = clavicle + 4;
  }
  for (int side = 0; side < 2; ++side) {
    const double x = side == 0 ? 1.0 : -1.0;
    const std::string p = side == 0 ? "L" : "R";
    const int up = static_cast<int>(s.joints.size());
    add_joint(s, p + "UpLeg", 1, {9 * x, -6, 0}, kZyx);
    add_joint(s, p + "Leg", up, {0, -40, 0}, kZyx);
    add_joint(s, p + "Foot", up + 1, {0, -40, 0}, kZxy);
    add_joint(s, p + "Toe", up + 2, {0, -6, 12}, kZyx);
    add_end_site(s, up + 3, {0, 0, 4});
  }
  // hips, spine, chest, head, arms (shoulder, elbow, wrist), legs (hip, knee, ankle, toe).
  r.majors = {s.find("Hips"), s.find("Spine"), s.find("Chest"), s.find("Head")};
  for (const char* name : {"LArm", "LForeArm", "LHand", "RArm", "RForeArm", "RHand", "LUpLeg", "LLeg", "LFoot",
                           "LToe", "RUpLeg", "RLeg", "RFoot", "RToe"})
    r.majors.push_back(s.find(name));
  return r;
}

// A smooth random motion on the rig: every rotation a few sinusoids (amplitude in degrees), the
// hips walking along +Z; `spin` degrees per frame of extra yaw on the hips (past +-180).
Clip make_motion(const TestRig& rig, int frames, double amplitude, std::uint64_t seed, double spin = 0.0,
                 double fps = 30.0) {
  Clip clip;
  clip.source = "synthetic.bvh";
  clip.skeleton = rig.skeleton;
  clip.frame_time = 1.0 / fps;
  clip.motion = MotionMatrix::Zero(frames, rig.skeleton.channel_count);
  Random random(seed);
  for (const Joint& j : rig.skeleton.joints) {
    for (size_t c = 0; c < j.channels.size(); ++c) {
      const int col = j.first_channel + static_cast<int>(c);
      if (is_position(j.channels[c])) {
        // Position channels replace the OFFSET: keep it (the ROOT dummy stays at the origin).
        for (int f = 0; f < frames; ++f) clip.motion(f, col) = j.offset[channel_axis(j.channels[c])];
        continue;
      }
      if (&j == &rig.skeleton.joints[rig.root]) continue;  // the still dummy
      const double a = amplitude * (0.3 + random.uniform());
      const double w = 0.05 + 0.2 * random.uniform();
      const double phase = 6.28 * random.uniform();
      for (int f = 0; f < frames; ++f) clip.motion(f, col) = a * std::sin(w * f + phase);
    }
  }
  const Joint& hips = rig.skeleton.joints[rig.hips];
  for (int f = 0; f < frames; ++f) {
    clip.motion(f, hips.first_channel + 2) = 3.0 * f;  // Zposition: walking
    clip.motion(f, hips.first_channel + 3) += spin * f;  // Zrotation of ZXY: not yaw, but it wraps
  }
  return clip;
}

Eigen::MatrixXd major_positions(const Clip& clip, const std::vector<int>& joints) {
  const Eigen::MatrixXd all = joint_positions(clip);
  Eigen::MatrixXd out(all.rows(), 3 * static_cast<Eigen::Index>(joints.size()));
  for (size_t c = 0; c < joints.size(); ++c) out.middleCols(3 * c, 3) = all.middleCols(3 * joints[c], 3);
  return out;
}

double max_distance(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  REQUIRE(a.rows() == b.rows());
  REQUIRE(a.cols() == b.cols());
  double worst = 0;
  for (Eigen::Index f = 0; f < a.rows(); ++f)
    for (Eigen::Index j = 0; j < a.cols() / 3; ++j)
      worst = std::max(worst, (a.block<1, 3>(f, 3 * j) - b.block<1, 3>(f, 3 * j)).norm());
  return worst;
}

// The largest change of any rotation channel between consecutive frames, degrees.
double max_euler_step(const Clip& clip) {
  double worst = 0;
  for (const Joint& j : clip.skeleton.joints)
    for (size_t c = 0; c < j.channels.size(); ++c) {
      if (!is_rotation(j.channels[c])) continue;
      const int col = j.first_channel + static_cast<int>(c);
      for (int f = 1; f < clip.frames(); ++f)
        worst = std::max(worst, std::abs(clip.motion(f, col) - clip.motion(f - 1, col)));
    }
  return worst;
}

double height_of(const Clip& clip) { return guess_units(clip).height; }

}  // namespace

TEST_CASE("exporting a take's own positions gives back every joint, fingers included", "[export]") {
  const TestRig rig = make_rig();
  const Clip a = make_motion(rig, 60, 25.0, 1);
  const Eigen::MatrixXd targets = major_positions(a, rig.majors);
  const ExportResult r = solve_export(a, rig.majors, targets, a.fps());
  const double h = height_of(a);
  CHECK(r.fit.max <= kExactFit * h);
  REQUIRE(r.clip.frames() == a.frames());
  CHECK(r.clip.frame_time == a.frame_time);
  // All joints (fingers, neck, clavicles, End Sites), not only the targets.
  CHECK(max_distance(joint_positions(r.clip), joint_positions(a)) <= kExactFit * h);
  // Joints with no target and no pivot role keep A's values exactly (up to unwrapping).
  const Joint& finger = rig.skeleton.joints[rig.finger];
  for (int f = 0; f < a.frames(); ++f)
    for (int c = 0; c < 3; ++c)
      CHECK(r.clip.motion(f, finger.first_channel + c) == a.motion(f, finger.first_channel + c));
}

TEST_CASE("a reachable pose of another motion is reproduced at every major joint", "[export]") {
  const TestRig rig = make_rig();
  const Clip a = make_motion(rig, 50, 20.0, 2);
  const Clip b = make_motion(rig, 50, 35.0, 3);  // the same skeleton, other rotations
  const Eigen::MatrixXd targets = major_positions(b, rig.majors);
  const ExportResult r = solve_export(a, rig.majors, targets, 30.0);
  const double h = height_of(a);
  // The pelvis is rigid and equal in both; the chest reaches head and shoulders through its
  // neck and clavicles; every other bone is a rigid single chain.
  CHECK(r.fit.max <= kExactFit * h);
  CHECK(max_distance(major_positions(r.clip, rig.majors), targets) <= kExactFit * h);
  // The still ROOT dummy is left alone; the trajectory went onto Hips' position channels.
  const Joint& root = rig.skeleton.joints[rig.root];
  for (int f = 0; f < r.clip.frames(); ++f)
    for (int c = 0; c < 6; ++c) CHECK(r.clip.motion(f, root.first_channel + c) == 0.0);
  const Joint& hips = rig.skeleton.joints[rig.hips];
  CHECK(r.clip.motion(10, hips.first_channel + 2) == Approx(b.motion(10, hips.first_channel + 2)));
}

TEST_CASE("export round trip: write, read back with our reader, FK at the majors", "[export]") {
  const TestRig rig = make_rig();
  const Clip a = make_motion(rig, 40, 20.0, 4);
  const Clip b = make_motion(rig, 40, 30.0, 5);
  const Eigen::MatrixXd targets = major_positions(b, rig.majors);
  const ExportResult r = solve_export(a, rig.majors, targets, 30.0);
  const Clip back = parse_bvh(format_bvh(r.clip), "roundtrip.bvh");
  REQUIRE(back.frames() == targets.rows());
  CHECK(max_distance(major_positions(back, rig.majors), targets) <= kExactFit * height_of(a));
  // The same channel layout and rotation orders as A.
  REQUIRE(back.skeleton.joints.size() == a.skeleton.joints.size());
  for (size_t j = 0; j < a.skeleton.joints.size(); ++j) {
    CHECK(back.skeleton.joints[j].name == a.skeleton.joints[j].name);
    CHECK(back.skeleton.joints[j].channels == a.skeleton.joints[j].channels);
  }
}

TEST_CASE("export unwraps Euler angles: no jump over 180 degrees", "[export]") {
  const TestRig rig = make_rig();
  const Clip a = make_motion(rig, 120, 20.0, 6);
  // Targets from a motion whose hips turn 7 degrees a frame: over two full turns.
  const Clip b = make_motion(rig, 120, 20.0, 7, 7.0);
  const ExportResult r = solve_export(a, rig.majors, major_positions(b, rig.majors), 30.0);
  CHECK(r.fit.max <= kExactFit * height_of(a));
  CHECK(max_euler_step(r.clip) < kMaxEulerStep);
  const double yaw_end = r.clip.motion(119, rig.skeleton.joints[rig.hips].first_channel + 3);
  CHECK(std::abs(yaw_end) > 360.0);  // kept going, not wrapped back into [-180, 180]
}

TEST_CASE("export resamples A to the output rate first", "[export]") {
  const TestRig rig = make_rig();
  const Clip a = make_motion(rig, 121, 20.0, 8, 0.0, 120.0);  // 1 s at 120 fps
  const Clip a30 = resample_clip(a, 30.0);
  const Eigen::MatrixXd targets = major_positions(a30, rig.majors);
  const ExportResult r = solve_export(a, rig.majors, targets, 30.0);
  REQUIRE(r.clip.frames() == 31);
  CHECK(r.clip.fps() == 30.0);
  CHECK(max_distance(joint_positions(r.clip), joint_positions(a30)) <= kExactFit * height_of(a));
  // Frame counts must agree with the resampled take.
  CHECK_THROWS_AS(solve_export(a, rig.majors, targets.topRows(30), 30.0), InputError);
}

TEST_CASE("export rejects bad targets", "[export]") {
  const TestRig rig = make_rig();
  const Clip a = make_motion(rig, 10, 20.0, 9);
  const Eigen::MatrixXd targets = major_positions(a, rig.majors);
  std::vector<int> joints = rig.majors;
  CHECK_THROWS_AS(solve_export(a, joints, targets.leftCols(targets.cols() - 3), 30.0), InputError);
  joints[3] = 6;  // an End Site
  CHECK_THROWS_AS(solve_export(a, joints, targets, 30.0), InputError);
  joints[3] = 999;
  CHECK_THROWS_AS(solve_export(a, joints, targets, 30.0), InputError);
  joints[3] = rig.majors[2];  // listed twice
  CHECK_THROWS_AS(solve_export(a, joints, targets, 30.0), InputError);
  Eigen::MatrixXd bad = targets;
  bad(3, 7) = NAN;
  CHECK_THROWS_WITH(solve_export(a, rig.majors, bad, 30.0), Catch::Contains("finite"));
  CHECK_THROWS_AS(export_fit(a, rig.majors, targets.topRows(5)), InputError);
}

namespace {

struct Blended {
  std::shared_ptr<const PreparedTakes> prepared;
  MixResult result;
};

Blended blend_files(const std::string& path_a, const std::string& path_b, double alpha) {
  auto a = std::make_shared<const Clip>(read_bvh_file(path_a));
  auto b = std::make_shared<const Clip>(read_bvh_file(path_b));
  Blended out;
  out.prepared = prepare_takes({a, b}, PrepareOptions{});
  DecomposeParams dp;
  dp.components = 8;
  dp.max_iterations = 30;
  const auto d = decompose_takes(*out.prepared, dp);
  test::BlendRun scratch;
  test::blend_into(*out.prepared, *d, alpha, MixParams(), scratch, out.result);
  return out;
}

// Exports a blend, writes and reads it back, and checks the acceptance bounds. Returns
// the read-back clip's major positions.
Eigen::MatrixXd check_blend_export(const Blended& blend) {
  const PreparedTakes& p = *blend.prepared;
  // A's rotations where the blend is in A's motion (its own timeline, trajectory/mixed_clock.h).
  const ExportResult r =
      solve_export_at(*p.takes[0].clip, export_joints(p), blend.result.motion.world, source_frames_in_clip(p, blend.result), p.fps);
  const Clip back = parse_bvh(format_bvh(r.clip), "blend.bvh");
  REQUIRE(back.frames() == blend.result.motion.world.rows());
  std::vector<int> joints;
  for (int major : p.majors) joints.push_back(p.takes[0].mapping.joint[major]);
  const Eigen::MatrixXd positions = major_positions(back, joints);
  const double h = guess_units(*p.takes[0].clip).height;
  const ExportFit fit = export_fit(back, joints, blend.result.motion.world);
  INFO(p.takes[0].clip->source << " / " << p.takes[1].clip->source << ": fit max " << fit.max << ", mean " << fit.mean
                        << ", height " << h);
  CHECK(fit.max <= kMaxFit * h);
  CHECK(fit.mean <= kMeanFit * h);
  CHECK(fit.max == Approx(r.fit.max).margin(1e-9 * h));
  CHECK(max_euler_step(back) < kMaxEulerStep);
  return positions;
}

}  // namespace

TEST_CASE("a real take paired with itself exports back to itself, fingers included", "[export]") {
  // CMU 142 (assets): near-gimbal-lock root, zero-length bones, fingers and thumbs at 120 fps.
  auto a = std::make_shared<const Clip>(read_bvh_file(test::asset("motions/cmu142_walk_happy.bvh")));
  const auto p = prepare_takes({a, a}, PrepareOptions{});
  // The blend at alpha 0 before synthesis: A itself, on A's own frames.
  const ExportResult r = solve_export(*p->takes[0].clip, export_joints(*p), p->takes[0].world, p->fps);
  const Clip a30 = resample_clip(*a, p->fps);
  const double h = guess_units(*a).height;
  // The reference is prepared in its mean bone lengths, a hair (0.06% of the height here) from
  // the file's chains of majors, which skip joints: the fit is that hair, and the export, on the
  // file's own bones, is the file itself.
  CHECK(r.fit.max <= 1e-3 * h);
  CHECK(max_distance(joint_positions(r.clip), joint_positions(a30)) <= kExactFit * h);
  CHECK(max_euler_step(r.clip) < kMaxEulerStep);
}

TEST_CASE("export of a real blend (assets, CMU): bounds, single-child chains tight", "[export]") {
  const Blended blend = blend_files(test::asset("motions/cmu142_walk_happy.bvh"),
                                    test::asset("motions/cmu142_walk_joy.bvh"), 0.5);
  const PreparedTakes& p = *blend.prepared;
  const Eigen::MatrixXd positions = check_blend_export(blend);
  // Every major joint below a joint with a single major child is placed by one rigid chain (or,
  // under the hips and chest, behind a pivot): it lands on the blend to rounding. Only the head
  // rests on CMU's two neck joints, whose bend A keeps.
  const double h = guess_units(*p.takes[0].clip).height;
  for (size_t c = 1; c < p.majors.size(); ++c) {
    if (p.majors[c] == static_cast<int>(MajorJoint::kHead)) continue;
    INFO(p.takes[0].names[c]);
    double worst = 0;
    for (Eigen::Index f = 0; f < positions.rows(); ++f)
      worst = std::max(worst, (positions.block<1, 3>(f, 3 * c) - blend.result.motion.world.block<1, 3>(f, 3 * c)).norm());
    CHECK(worst <= 1e-7 * h);
  }
}

TEST_CASE("export of real blends from ../shared/motions: within the acceptance bounds", "[export]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  const std::pair<const char*, const char*> pairs[] = {
      {"bandai_walk_normal.bvh", "bandai_walk_tired.bvh"},
      {"bandai_walk_proud.bvh", "bandai_walk_old.bvh"},
      {"cmu142_walk_clumsy.bvh", "bandai_walk_happy.bvh"},  // across conventions, CMU as A
  };
  for (const auto& [a, b] : pairs) {
    const Blended blend = blend_files(test::shared_motion(a), test::shared_motion(b), 0.5);
    check_blend_export(blend);
  }
}

TEST_CASE("export_blend_bvh writes a file Blender-style readers see as the blend", "[export]") {
  const Blended blend = blend_files(test::asset("motions/cmu142_walk_marching.bvh"),
                                    test::asset("motions/cmu142_walk_clumsy.bvh"), 0.3);
  const std::string path = (std::filesystem::temp_directory_path() / "mostyle_export_solve_test.bvh").string();
  const PreparedTakes& p = *blend.prepared;
  const ExportResult r = export_blend_bvh(*p.takes[0].clip, export_joints(p), blend.result.motion.world,
                                          source_frames_in_clip(p, blend.result), p.fps, path);
  const Clip back = read_bvh_file(path);
  CHECK(back.frames() == blend.result.motion.world.rows());
  CHECK(back.fps() == blend.prepared->fps);
  CHECK(r.fit.max <= kMaxFit * guess_units(*blend.prepared->takes[0].clip).height);
  std::remove(path.c_str());
}
