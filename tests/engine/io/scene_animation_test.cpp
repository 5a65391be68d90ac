#include "engine/io/scene_animation.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "engine/base/error.h"
#include "engine/kinematics/kinematics.h"

using namespace mostyle;
using Catch::Matchers::Contains;

namespace {

constexpr double kTight = 1e-12;

KeyTrack track(int node, TrackTarget target, KeyInterpolation interpolation, std::vector<double> times,
               std::vector<double> values) {
  KeyTrack t;
  t.node = node;
  t.target = target;
  t.interpolation = interpolation;
  t.times = std::move(times);
  const int width = target == TrackTarget::kRotation ? 4 : 3;
  t.values = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      values.data(), static_cast<Eigen::Index>(values.size() / width), width);
  return t;
}

SceneNode node(const std::string& name, int parent, Eigen::Vector3d t = Eigen::Vector3d::Zero()) {
  SceneNode n;
  n.name = name;
  n.parent = parent;
  n.translation = t;
  return n;
}

}  // namespace

TEST_CASE("sample_track: STEP holds the key at or before t", "[scene_animation]") {
  const KeyTrack t = track(0, TrackTarget::kTranslation, KeyInterpolation::kStep, {0, 1}, {0, 0, 0, 2, 4, 6});
  CHECK(sample_track(t, -1)(0) == 0);
  CHECK(sample_track(t, 0.99)(1) == 0);
  CHECK(sample_track(t, 1)(2) == 6);
  CHECK(sample_track(t, 5)(1) == 4);
}

TEST_CASE("sample_track: LINEAR interpolates, slerps rotations on the shorter arc", "[scene_animation]") {
  const KeyTrack t = track(0, TrackTarget::kTranslation, KeyInterpolation::kLinear, {0, 1}, {0, 0, 0, 2, 4, 6});
  const Eigen::VectorXd v = sample_track(t, 0.25);
  CHECK(v(0) == Approx(0.5).epsilon(kTight));
  CHECK(v(1) == Approx(1.0).epsilon(kTight));
  CHECK(v(2) == Approx(1.5).epsilon(kTight));
  const double s45 = std::sin(M_PI / 4), c45 = std::cos(M_PI / 4);
  // Identity to 90 degrees about Z, the second key written with the opposite sign: halfway is
  // 45 degrees about Z, not the long way round.
  const KeyTrack r =
      track(0, TrackTarget::kRotation, KeyInterpolation::kLinear, {0, 2}, {0, 0, 0, 1, 0, 0, -s45, -c45});
  Eigen::VectorXd q = sample_track(r, 1.0);
  if (q(3) < 0) q = -q;
  CHECK(q(2) == Approx(std::sin(M_PI / 8)).margin(kTight));
  CHECK(q(3) == Approx(std::cos(M_PI / 8)).margin(kTight));
  CHECK(q.norm() == Approx(1.0).epsilon(kTight));
}

TEST_CASE("sample_track: CUBICSPLINE is glTF's Hermite spline with tangents times the interval", "[scene_animation]") {
  // x: value 0 with out-tangent 1 at t = 0, value 1 with in-tangent 0 at t = 2. At s = 0.5
  // (t = 1), dt = 2: 2 * (1/8 - 1/2 + 1/2) * 1 + (-1/4 + 3/4) * 1 = 0.25 + 0.5 = 0.75.
  // Rows per key: in-tangent, value, out-tangent.
  const KeyTrack t = track(0, TrackTarget::kTranslation, KeyInterpolation::kCubicSpline, {0, 2},
                           {9, 9, 9, 0, 0, 0, 1, 0, 0,  //
                            0, 0, 0, 1, 0, 0, 9, 9, 9});
  CHECK(sample_track(t, 1.0)(0) == Approx(0.75).epsilon(kTight));
  CHECK(sample_track(t, 0.0)(0) == 0.0);  // keys are values, tangents never leak in
  CHECK(sample_track(t, 2.0)(0) == 1.0);
  // A quarter: s = 0.25: 2 * (1/64 - 2/16 + 1/4) + (-2/64 + 3/16) = 0.28125 + 0.15625 = 0.4375.
  CHECK(sample_track(t, 0.5)(0) == Approx(0.4375).epsilon(kTight));
}

TEST_CASE("scene_take_to_clip: the keyed nodes as a skeleton, the nodes above folded in", "[scene_animation]") {
  AnimatedScene scene;
  scene.source = "rig.glb";
  SceneNode armature = node("Armature", -1);
  armature.scale = Eigen::Vector3d::Constant(100);
  armature.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()));
  scene.nodes = {armature, node("Hips", 0, {1, 2, 3}), node("Spine", 1, {0, 1, 0}), node("Mesh", 0)};
  SceneTake take;
  take.name = "walk";
  take.tracks.push_back(track(1, TrackTarget::kTranslation, KeyInterpolation::kLinear, {0, 1}, {1, 2, 3, 1, 2, 4}));
  const double s = std::sin(M_PI / 4), c = std::cos(M_PI / 4);
  take.tracks.push_back(track(2, TrackTarget::kRotation, KeyInterpolation::kLinear, {0, 1}, {0, 0, 0, 1, 0, 0, s, c}));
  scene.takes.push_back(take);
  SceneClipOptions o;
  o.fps = 10;
  const Clip clip = scene_take_to_clip(scene, 0, o);
  REQUIRE(clip.skeleton.joints.size() == 2);
  CHECK(clip.skeleton.joints[0].name == "Hips");
  CHECK(clip.skeleton.joints[1].name == "Spine");
  CHECK(clip.frames() == 11);
  CHECK(clip.frame_time == Approx(0.1));
  // Hips in the world: 100 * Rx(90) * (1, 2, 3 + t); Spine 100 above it along the Armature's Y.
  const Eigen::MatrixXd p = joint_positions(clip);
  const Eigen::Matrix3d rx = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  for (int f : {0, 5, 10}) {
    const Eigen::Vector3d hips = 100 * rx * Eigen::Vector3d(1, 2, 3 + f / 10.0);
    CHECK((p.block<1, 3>(f, 0).transpose() - hips).norm() < 1e-9);
    CHECK((p.block<1, 3>(f, 3).transpose() - (hips + 100 * rx * Eigen::Vector3d(0, 1, 0))).norm() < 1e-9);
  }
  CHECK(clip.skeleton.joints[1].channels.size() == 3);  // a rigid bone: no position channels
}

TEST_CASE("scene_take_to_clip: bad takes are one sentence naming file and animation", "[scene_animation]") {
  AnimatedScene scene;
  scene.source = "two.glb";
  scene.nodes = {node("A", -1), node("B", -1)};
  SceneTake take;
  take.name = "both";
  take.tracks.push_back(track(0, TrackTarget::kTranslation, KeyInterpolation::kLinear, {0}, {0, 0, 0}));
  take.tracks.push_back(track(1, TrackTarget::kTranslation, KeyInterpolation::kLinear, {0}, {0, 0, 0}));
  scene.takes.push_back(take);
  CHECK_THROWS_WITH(scene_take_to_clip(scene, 0),
                    Contains("two.glb: the animations' nodes form several skeletons (rooted at 'A', 'B') and "
                             "animation 'both' moves more than one"));
  scene.takes[0].tracks.pop_back();
  scene.takes[0].tracks[0].times = {0, 1};
  scene.takes[0].tracks[0].values.resize(2, 3);
  scene.takes[0].tracks[0].values.setZero();
  SceneClipOptions o;
  o.fps = 1000;
  o.max_bytes = 1000;
  CHECK_THROWS_WITH(scene_take_to_clip(scene, 0, o), Contains("more than the limit of 1000 bytes"));
  scene.takes[0].tracks[0].times = {1, 0};
  CHECK_THROWS_WITH(scene_take_to_clip(scene, 0), Contains("two.glb: animation 'both': the translation keys of node 'A' have times that do not increase"));
  scene.takes[0].tracks.clear();
  CHECK_THROWS_WITH(scene_take_to_clip(scene, 0), Contains("keys no node"));
}

TEST_CASE("default_take_rate: the file's, else the keys' spacing, else 30", "[scene_animation]") {
  AnimatedScene scene;
  scene.nodes = {node("A", -1)};
  SceneTake take;
  take.tracks.push_back(track(0, TrackTarget::kTranslation, KeyInterpolation::kLinear, {0, 0.04, 0.08},
                              {0, 0, 0, 1, 1, 1, 2, 2, 2}));
  scene.takes.push_back(take);
  CHECK(default_take_rate(scene, 0) == Approx(25.0).epsilon(1e-12));
  scene.frame_rate = 24;
  CHECK(default_take_rate(scene, 0) == 24.0);
  scene.frame_rate = 0;
  scene.takes[0].tracks[0].times = {0};
  scene.takes[0].tracks[0].values.conservativeResize(1, 3);
  CHECK(default_take_rate(scene, 0) == 30.0);
}

TEST_CASE("scene_take_to_clip: every take of a file on one skeleton, a joint a take does not key at rest",
          "[scene_animation]") {
  AnimatedScene scene;
  scene.source = "rig.glb";
  SceneNode armature = node("Armature", -1);
  armature.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()));
  scene.nodes = {armature,                        // 0
                 node("Hips", 0, {0, 1, 0}),      // 1
                 node("Left", 1, {1, 0, 0}),      // 2
                 node("Right", 1, {-1, 0, 0}),    // 3
                 node("RightEnd", 3, {0, -1, 0}), // 4: keyed by no take
                 node("Mesh", 0)};                // 5
  const double s = std::sin(M_PI / 4), c = std::cos(M_PI / 4);
  SceneTake a;
  a.name = "a";
  a.tracks.push_back(track(1, TrackTarget::kTranslation, KeyInterpolation::kLinear, {0, 1}, {0, 1, 0, 0, 2, 0}));
  a.tracks.push_back(track(2, TrackTarget::kRotation, KeyInterpolation::kLinear, {0, 1}, {0, 0, 0, 1, 0, 0, s, c}));
  SceneTake b;
  b.name = "b";
  b.tracks.push_back(track(3, TrackTarget::kRotation, KeyInterpolation::kLinear, {0, 2}, {0, 0, 0, 1, 0, 0, s, c}));
  // Right moved off its rest place in b: position channels in both takes.
  b.tracks.push_back(track(3, TrackTarget::kTranslation, KeyInterpolation::kLinear, {0, 2}, {-1, 0, 0, -2, 0, 0}));
  SceneTake mesh_only;
  mesh_only.name = "mesh";
  mesh_only.tracks.push_back(track(5, TrackTarget::kScale, KeyInterpolation::kLinear, {0, 1}, {1, 1, 1, 2, 2, 2}));
  scene.takes = {a, b, mesh_only};
  SceneClipOptions o;
  o.fps = 10;

  SECTION("no skin: the nodes any take keys, and those between them") {
    const SceneSkeleton sk = scene_skeleton(scene);
    CHECK_FALSE(sk.from_skins);
    // Mesh is keyed too, by a take of its own: the skeleton roots at the Armature then.
    CHECK(scene.nodes[sk.root()].name == "Armature");
    scene.takes.pop_back();
    const SceneSkeleton without_mesh = scene_skeleton(scene);
    REQUIRE(without_mesh.nodes == std::vector<int>{1, 2, 3});
    const Clip ca = scene_take_to_clip(scene, 0, o), cb = scene_take_to_clip(scene, 1, o);
    REQUIRE(ca.skeleton.joints.size() == 3);
    for (size_t j = 0; j < 3; ++j) {
      CHECK(ca.skeleton.joints[j].name == cb.skeleton.joints[j].name);
      CHECK(ca.skeleton.joints[j].channels == cb.skeleton.joints[j].channels);
      CHECK((ca.skeleton.joints[j].offset - cb.skeleton.joints[j].offset).norm() < kTight);
    }
    CHECK(ca.skeleton.joints[2].channels.size() == 6);  // Right: moved in b
    CHECK(ca.skeleton.joints[1].channels.size() == 3);  // Left: turns only
    // In a, Right is where the rest pose puts it: the Armature turns -X into +Z.
    const Eigen::MatrixXd p = joint_positions(ca);
    for (int f : {0, 10}) {
      const Eigen::Vector3d hips(0, 1 + f / 10.0, 0);
      CHECK((p.block<1, 3>(f, 6).transpose() - (hips + Eigen::Vector3d(0, 0, 1))).norm() < 1e-9);
    }
    const std::vector<TakeInfo> infos = scene_take_infos(scene);
    CHECK(infos[0].moves == 2);
    CHECK(infos[1].moves == 1);
  }
  SECTION("a skin: its joints, a leaf no take keys among them") {
    scene.skin_joints = {1, 2, 3, 4};
    const SceneSkeleton sk = scene_skeleton(scene);
    CHECK(sk.from_skins);
    CHECK(sk.nodes == std::vector<int>{1, 2, 3, 4});
    const Clip ca = scene_take_to_clip(scene, 0, o), cb = scene_take_to_clip(scene, 1, o);
    REQUIRE(ca.skeleton.joints.size() == 4);
    REQUIRE(cb.skeleton.joints.size() == 4);
    CHECK(ca.skeleton.channel_count == cb.skeleton.channel_count);
    // The rest pose (rest_positions) is the file's: the Armature's quarter turn included.
    const std::vector<Eigen::Vector3d> rest = rest_positions(ca.skeleton);
    CHECK((rest[2] - rest[0] - Eigen::Vector3d(0, 0, 1)).norm() < 1e-12);
    CHECK((rest[3] - rest[0] - Eigen::Vector3d(0, -1, 1)).norm() < 1e-12);
    // b keys none of Left: it stays at rest, turned with the hips only.
    const Eigen::MatrixXd p = joint_positions(cb);
    CHECK((p.block<1, 3>(0, 3) - p.block<1, 3>(0, 0) - Eigen::RowVector3d(0, 0, -1)).norm() < 1e-9);
    // The take that keys only the mesh moves nothing of the skeleton.
    CHECK_THROWS_WITH(scene_take_to_clip(scene, 2, o),
                      Contains("rig.glb: animation 'mesh' keys none of the skeleton's joints (rooted at 'Hips')"));
    CHECK(scene_take_infos(scene)[2].moves == 0);
  }
}

TEST_CASE("scene_take_to_clip: end bones no take keys stay in the skeleton, as End Sites", "[scene_animation]") {
  // An FBX rig as assimp gives it: LimbNodes (limb) under an armature; Leg and Head keyed, the
  // end bones LegEnd and HeadTop keyed by no take, a prop (a Null) on the head.
  AnimatedScene scene;
  scene.source = "rig.fbx";
  const auto limb = [](SceneNode n) {
    n.limb = true;
    return n;
  };
  scene.nodes = {node("Armature", -1),                  // 0
                 limb(node("Hips", 0, {0, 1, 0})),      // 1
                 limb(node("Leg", 1, {0, -0.5, 0})),    // 2
                 limb(node("LegEnd", 2, {0, -0.5, 0})), // 3
                 limb(node("Head", 1, {0, 0.5, 0})),    // 4
                 limb(node("HeadTop", 4, {0, 0.2, 0})), // 5
                 node("Prop", 4, {0.3, 0, 0})};         // 6
  const double s = std::sin(M_PI / 4), c = std::cos(M_PI / 4);
  SceneTake walk;
  walk.name = "walk";
  walk.tracks.push_back(track(1, TrackTarget::kTranslation, KeyInterpolation::kLinear, {0, 1}, {0, 1, 0, 0, 1, 1}));
  walk.tracks.push_back(track(2, TrackTarget::kRotation, KeyInterpolation::kLinear, {0, 1}, {0, 0, 0, 1, 0, 0, s, c}));
  walk.tracks.push_back(track(4, TrackTarget::kRotation, KeyInterpolation::kLinear, {0, 1}, {0, 0, 0, 1, s, 0, 0, c}));
  scene.takes = {walk};
  SceneClipOptions o;
  o.fps = 2;

  const SceneSkeleton sk = scene_skeleton(scene);
  CHECK(sk.nodes == std::vector<int>{1, 2, 3, 4, 5});  // the prop is no bone
  const Clip clip = scene_take_to_clip(scene, 0, o);
  REQUIRE(clip.skeleton.joints.size() == 5);
  CHECK(clip.skeleton.joint_count_without_end_sites() == 3);
  for (int j : {2, 4}) {
    INFO(clip.skeleton.joints[j].name);
    CHECK(clip.skeleton.joints[j].end_site);
    CHECK(clip.skeleton.joints[j].channels.empty());
  }
  CHECK(clip.skeleton.joints[2].name == "LegEnd");
  CHECK(clip.skeleton.find("LegEnd") == -1);  // End Sites match no name, as BVH's
  // The end bones follow their joints: the leg's a quarter turn about Z at t = 1, the head's
  // about X.
  const Eigen::MatrixXd p = joint_positions(clip);
  CHECK((p.block<1, 3>(2, 6) - Eigen::RowVector3d(0.5, 0.5, 1)).norm() < 1e-9);
  CHECK((p.block<1, 3>(2, 12) - Eigen::RowVector3d(0, 1.5, 1.2)).norm() < 1e-9);
  CHECK(clip.skeleton.metres_per_unit == 0.0);  // FBX as assimp reads it states no unit

  // A take that turns an end bone makes it a joint in every take.
  SceneTake tip;
  tip.name = "tip";
  tip.tracks.push_back(track(3, TrackTarget::kRotation, KeyInterpolation::kLinear, {0, 1}, {0, 0, 0, 1, 0, 0, s, c}));
  scene.takes.push_back(tip);
  const Clip again = scene_take_to_clip(scene, 0, o);
  CHECK_FALSE(again.skeleton.joints[2].end_site);
  CHECK(again.skeleton.joints[2].channels.size() == 3);
  CHECK(again.skeleton.joints[4].end_site);
  // A unit the format fixes comes with the clip.
  scene.metres_per_unit = 1.0;
  CHECK(scene_take_to_clip(scene, 0, o).skeleton.metres_per_unit == 1.0);
}

TEST_CASE("scene_take_to_clip: two characters in one file, each take on its own one's skeleton",
          "[scene_animation]") {
  AnimatedScene scene;
  scene.source = "pair.glb";
  scene.nodes = {node("A", -1), node("A1", 0, {0, 1, 0}), node("A2", 0, {1, 0, 0}), node("B", -1),
                 node("B1", 3, {0, 1, 0})};
  SceneTake a1, a2, b;
  a1.name = "a1";
  a1.tracks.push_back(track(1, TrackTarget::kTranslation, KeyInterpolation::kLinear, {0}, {0, 1, 0}));
  a2.name = "a2";
  a2.tracks.push_back(track(2, TrackTarget::kTranslation, KeyInterpolation::kLinear, {0}, {1, 0, 0}));
  b.name = "b";
  b.tracks.push_back(track(4, TrackTarget::kTranslation, KeyInterpolation::kLinear, {0}, {0, 1, 0}));
  scene.takes = {a1, a2, b};
  CHECK_THROWS_WITH(scene_skeleton(scene), Contains("pair.glb: the animations' nodes form several skeletons"));
  // A's takes share A's skeleton (A, A1, A2), each keying a part of it; b reads B's.
  CHECK(scene_skeleton(scene, 0).nodes == std::vector<int>{0, 1, 2});
  CHECK(scene_skeleton(scene, 1).nodes == std::vector<int>{0, 1, 2});
  CHECK(scene_skeleton(scene, 2).nodes == std::vector<int>{4});
  CHECK(scene_take_to_clip(scene, 1).skeleton.joints.size() == 3);
  const std::vector<TakeInfo> infos = scene_take_infos(scene);
  CHECK(infos[0].moves == 1);
  CHECK(infos[2].moves == 1);
}
