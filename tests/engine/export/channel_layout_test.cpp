#include "engine/export/channel_layout.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/export/export_solve.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/io/bvh/bvh_write.h"
#include "engine/base/error.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/units.h"
#include "tests/engine/synthetic_motion.h"
#include "tests/test_data.h"

using namespace mostyle;
using mostyle::test::Random;

namespace {

// The same joint positions, up to rounding; relative to the skeleton's height.
constexpr double kSamePlace = 1e-9;
// Where readers disagree (Bandai as its source lays it out, read by three.js), some joint is at
// least this far off, relative to the height (the hips alone are an OFFSET, ~94 cm, too high).
constexpr double kReadersApart = 0.5;
// Targets that A's own joints reach: the solve places them (to rounding, export_solve_test
// checks it); here only a bound that shows the file holds the solve.
constexpr double kFit = 1e-6;

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

using C = Channel;
const std::vector<Channel> kPosZxy = {C::kXposition, C::kYposition, C::kZposition,
                                      C::kZrotation, C::kXrotation, C::kYrotation};
const std::vector<Channel> kPosZyx = {C::kXposition, C::kYposition, C::kZposition,
                                      C::kZrotation, C::kYrotation, C::kXrotation};
const std::vector<Channel> kPosXyz = {C::kXposition, C::kYposition, C::kZposition,
                                      C::kXrotation, C::kYrotation, C::kZrotation};
// Rotations first, positions after them in another axis order.
const std::vector<Channel> kZxyPosYzx = {C::kZrotation, C::kXrotation, C::kYrotation,
                                         C::kYposition, C::kZposition, C::kXposition};
// One position channel: Blender and our FK read the missing axes as 0, not as the OFFSET's.
const std::vector<Channel> kPosZOnly = {C::kZposition, C::kZrotation, C::kXrotation, C::kYrotation};

// Bandai's layout built in code: position channels on every joint, a still ROOT dummy, the
// trajectory on its child Hips (whose OFFSET is not what its channels say), constant position
// channels elsewhere. Plus what other files may do: positions after the rotations and in another
// axis order (Chest), a single position channel (Toes), mixed rotation orders.
struct Rig {
  Skeleton skeleton;
  std::vector<int> majors;  // the joints an export places (as export_solve_test's rig)
  int root = 0, hips = 1, spine = 2, chest = 3, toes = -1;
};

Rig make_rig() {
  Rig r;
  Skeleton& s = r.skeleton;
  add_joint(s, "joint_Root", -1, {0, 0, 0}, kPosZxy);    // 0
  add_joint(s, "Hips", 0, {0, 94, -3}, kPosZxy);         // 1
  add_joint(s, "Spine", 1, {0, 16, 0}, kPosZyx);         // 2
  add_joint(s, "Chest", 2, {0, 9, 0.5}, kZxyPosYzx);     // 3
  add_joint(s, "Neck", 3, {0, 16, 0}, kPosXyz);          // 4
  add_joint(s, "Head", 4, {0, 6, 1}, kPosZxy);           // 5
  add_end_site(s, 5, {0, 8, 0});
  for (int side = 0; side < 2; ++side) {
    const double x = side == 0 ? 1.0 : -1.0;
    const std::string p = side == 0 ? "_L" : "_R";
    const int shoulder = static_cast<int>(s.joints.size());
    add_joint(s, "Shoulder" + p, 3, {5 * x, 13, 0}, kPosZxy);
    add_joint(s, "UpperArm" + p, shoulder, {5 * x, 0, 0}, kPosZxy);
    add_joint(s, "LowerArm" + p, shoulder + 1, {24 * x, 0, 0}, kPosZyx);
    add_joint(s, "Hand" + p, shoulder + 2, {22 * x, 0, 0}, kPosZxy);
    add_end_site(s, shoulder + 3, {4 * x, 0, 0});
  }
  for (int side = 0; side < 2; ++side) {
    const double x = side == 0 ? 1.0 : -1.0;
    const std::string p = side == 0 ? "_L" : "_R";
    const int up = static_cast<int>(s.joints.size());
    add_joint(s, "UpperLeg" + p, 1, {6.5 * x, -2, 0}, kPosZxy);
    add_joint(s, "LowerLeg" + p, up, {0, -39, 0}, kPosZxy);
    add_joint(s, "Foot" + p, up + 1, {0, -41, 0}, kPosZxy);
    add_joint(s, "Toes" + p, up + 2, {0, -5, 11}, kPosZOnly);
    add_end_site(s, up + 3, {0, 0, 4});
    if (side == 0) r.toes = up + 3;
  }
  for (const char* name : {"Hips", "Spine", "Chest", "Head", "UpperArm_L", "LowerArm_L", "Hand_L", "UpperArm_R",
                           "LowerArm_R", "Hand_R", "UpperLeg_L", "LowerLeg_L", "Foot_L", "Toes_L", "UpperLeg_R",
                           "LowerLeg_R", "Foot_R", "Toes_R"})
    r.majors.push_back(s.find(name));
  return r;
}

// A smooth random motion on the rig: rotations a few sinusoids (degrees), the ROOT still at 0,
// the hips swaying and walking along +Z in their position channels, every other position
// channel its OFFSET's value for that axis (as in the Bandai files).
Clip make_motion(const Rig& rig, int frames, std::uint64_t seed) {
  Clip clip;
  clip.source = "bandai_like.bvh";
  clip.skeleton = rig.skeleton;
  clip.frame_time = 1.0 / 30.0;
  clip.motion = MotionMatrix::Zero(frames, rig.skeleton.channel_count);
  Random random(seed);
  for (int j = 0; j < static_cast<int>(rig.skeleton.joints.size()); ++j) {
    const Joint& joint = rig.skeleton.joints[j];
    if (j == rig.root) continue;
    for (size_t c = 0; c < joint.channels.size(); ++c) {
      const int col = joint.first_channel + static_cast<int>(c);
      const int axis = channel_axis(joint.channels[c]);
      if (is_position(joint.channels[c]) && j != rig.hips) {
        for (int f = 0; f < frames; ++f) clip.motion(f, col) = joint.offset[axis];
        continue;
      }
      const double a = is_position(joint.channels[c]) ? 2.0 : 25.0 * (0.3 + random.uniform());
      const double w = 0.05 + 0.2 * random.uniform();
      const double phase = 6.28 * random.uniform();
      for (int f = 0; f < frames; ++f) clip.motion(f, col) = a * std::sin(w * f + phase);
    }
  }
  const Joint& hips = rig.skeleton.joints[rig.hips];
  for (int f = 0; f < frames; ++f) {
    clip.motion(f, hips.first_channel + 1) += 90.0;      // Yposition: hips height
    clip.motion(f, hips.first_channel + 2) = 3.0 * f;   // Zposition: walking
  }
  return clip;
}

// The clip as a reader finds it in the file we write (format_bvh: a root's OFFSET is written 0
// when it has position channels).
Clip as_written(const Clip& clip) { return parse_bvh(format_bvh(clip), clip.source); }

// Joint positions (frames x 3*joints, End Sites included) as three.js's BVHLoader and other
// game-side readers place them: a joint's position channels are ADDED to its OFFSET (an axis
// without a channel adds 0), where Blender and our FK let them replace it. Rotations as ours,
// channel by channel in file order.
Eigen::MatrixXd threejs_positions(const Clip& clip) {
  const std::vector<Joint>& joints = clip.skeleton.joints;
  const size_t n = joints.size();
  Eigen::MatrixXd out(clip.frames(), 3 * static_cast<Eigen::Index>(n));
  std::vector<Eigen::Matrix3d> rotation(n);
  std::vector<Eigen::Vector3d> position(n);
  for (int f = 0; f < clip.frames(); ++f) {
    const double* row = clip.motion.row(f).data();
    for (size_t j = 0; j < n; ++j) {
      const Joint& joint = joints[j];
      Eigen::Vector3d translation = joint.offset;
      for (size_t c = 0; c < joint.channels.size(); ++c)
        if (is_position(joint.channels[c]))
          translation[channel_axis(joint.channels[c])] += row[joint.first_channel + c];
      const Eigen::Matrix3d local = joint_local_rotation(joint, row);
      if (joint.parent < 0) {
        rotation[j] = local;
        position[j] = translation;
      } else {
        rotation[j] = rotation[joint.parent] * local;
        position[j] = position[joint.parent] + rotation[joint.parent] * translation;
      }
      out.block<1, 3>(f, 3 * static_cast<Eigen::Index>(j)) = position[j].transpose();
    }
  }
  return out;
}

// The largest distance between the same joint at the same frame in two position matrices.
double max_distance(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  REQUIRE(a.rows() == b.rows());
  REQUIRE(a.cols() == b.cols());
  double worst = 0;
  for (Eigen::Index f = 0; f < a.rows(); ++f)
    for (Eigen::Index j = 0; j < a.cols() / 3; ++j)
      worst = std::max(worst, (a.block<1, 3>(f, 3 * j) - b.block<1, 3>(f, 3 * j)).norm());
  return worst;
}

double height_of(const Clip& clip) { return guess_units(clip).height; }

bool has_position(const Joint& joint) {
  for (Channel c : joint.channels)
    if (is_position(c)) return true;
  return false;
}

// Invariants of a clip in the rotations layout made from `source`.
void check_rotations_layout(const Clip& source, const Clip& out) {
  REQUIRE(out.skeleton.joints.size() == source.skeleton.joints.size());
  CHECK(out.source == source.source);
  CHECK(out.frame_time == source.frame_time);
  CHECK(out.frames() == source.frames());
  int count = 0;
  for (size_t j = 0; j < out.skeleton.joints.size(); ++j) {
    const Joint& a = source.skeleton.joints[j];
    const Joint& b = out.skeleton.joints[j];
    INFO(a.name);
    CHECK(b.name == a.name);
    CHECK(b.parent == a.parent);
    CHECK(b.end_site == a.end_site);
    CHECK(b.first_channel == count);
    count += static_cast<int>(b.channels.size());
    // The rotation channels, in the source's order, with the source's values.
    std::vector<int> rotations_a, rotations_b;
    for (size_t c = 0; c < a.channels.size(); ++c)
      if (is_rotation(a.channels[c])) rotations_a.push_back(static_cast<int>(c));
    for (size_t c = 0; c < b.channels.size(); ++c)
      if (is_rotation(b.channels[c])) rotations_b.push_back(static_cast<int>(c));
    REQUIRE(rotations_a.size() == rotations_b.size());
    int changed = 0;  // values that differ (one CHECK, not one per value of a long take)
    for (size_t k = 0; k < rotations_a.size(); ++k) {
      CHECK(b.channels[rotations_b[k]] == a.channels[rotations_a[k]]);
      for (int f = 0; f < out.frames(); ++f)
        changed += out.motion(f, b.first_channel + rotations_b[k]) !=
                   source.motion(f, a.first_channel + rotations_a[k]);
    }
    CHECK(changed == 0);
  }
  CHECK(out.skeleton.channel_count == count);
  CHECK(out.motion.cols() == count);
}

}  // namespace

TEST_CASE("channel layouts are named as --channels takes them", "[export][layout]") {
  CHECK(std::string(channel_layout_name(ChannelLayout::kAsSource)) == "as-source");
  CHECK(std::string(channel_layout_name(ChannelLayout::kRotations)) == "rotations");
  CHECK(parse_channel_layout("as-source") == ChannelLayout::kAsSource);
  CHECK(parse_channel_layout("rotations") == ChannelLayout::kRotations);
  for (const char* bad : {"", "rotation", "Rotations", "as_source", "source", "rotations "}) {
    INFO(bad);
    CHECK_THROWS_AS(parse_channel_layout(bad), InputError);
  }
  CHECK_THROWS_WITH(parse_channel_layout("positions"), Catch::Contains("as-source or rotations") &&
                                                           Catch::Contains("'positions'"));
}

TEST_CASE("the rotations layout keeps every joint where our FK puts it, on a Bandai-like clip", "[export][layout]") {
  const Rig rig = make_rig();
  const Clip a = make_motion(rig, 90, 7);
  const double h = height_of(a);
  REQUIRE(h > 0);
  const Clip r = with_rotation_channels(a);
  check_rotations_layout(a, r);
  const Eigen::MatrixXd ours = joint_positions(a);
  CHECK(max_distance(joint_positions(r), ours) <= kSamePlace * h);
  CHECK(max_distance(joint_positions(as_written(r)), ours) <= kSamePlace * h);

  // The root and the trajectory child (Hips) keep all six channels; Hips' OFFSET is 0 so that
  // readers adding it read its channels alone. Every other joint has rotations only.
  const std::vector<Joint>& joints = r.skeleton.joints;
  CHECK(joints[rig.root].channels == kPosZxy);
  CHECK(joints[rig.hips].channels == kPosZxy);
  CHECK(joints[rig.hips].offset == Eigen::Vector3d::Zero());
  for (size_t j = 2; j < joints.size(); ++j) {
    INFO(joints[j].name);
    CHECK_FALSE(has_position(joints[j]));
  }
  CHECK(r.skeleton.channel_count == 6 + 6 + 3 * (a.skeleton.joint_count_without_end_sites() - 2));
  // Constant channels become the OFFSET, Blender's reading of them: all three axes, so the toe
  // with only a Zposition channel (11) gets OFFSET (0, 0, 11), not its file OFFSET (0, -5, 11).
  CHECK(joints[rig.spine].offset == Eigen::Vector3d(0, 16, 0));
  CHECK(joints[rig.chest].offset == Eigen::Vector3d(0, 9, 0.5));
  CHECK(joints[rig.toes].offset == Eigen::Vector3d(0, 0, 11));
  CHECK(joints[rig.toes].channels == std::vector<Channel>{C::kZrotation, C::kXrotation, C::kYrotation});
}

TEST_CASE("on the rotations layout three.js-style readers agree with ours, on Bandai's own they do not",
          "[export][layout]") {
  const Rig rig = make_rig();
  const Clip a = make_motion(rig, 90, 11);
  const double h = height_of(a);
  const Eigen::MatrixXd ours = joint_positions(a);
  // The file as A lays it out: three.js adds every OFFSET (hips 94 too high, bones doubled).
  CHECK(max_distance(threejs_positions(as_written(a)), ours) > kReadersApart * h);
  // The rotations layout: every reader places every joint as we do.
  const Clip written = as_written(with_rotation_channels(a));
  CHECK(max_distance(threejs_positions(written), ours) <= kSamePlace * h);
  CHECK(max_distance(joint_positions(written), ours) <= kSamePlace * h);
}

TEST_CASE("a file without position channels below the root is its own rotations layout (CMU)", "[export][layout]") {
  const Clip a = read_bvh_file(test::asset("motions/cmu142_walk_happy.bvh"));
  const double h = height_of(a);
  CHECK(constant_offsets_below_root(a));
  CHECK(default_channel_layout(a) == ChannelLayout::kRotations);
  const Clip r = with_rotation_channels(a);
  check_rotations_layout(a, r);
  CHECK(format_bvh(r) == format_bvh(a));
  // Readers agree on it already (the root's OFFSET is written 0): the three.js reading here is
  // the one the other tests rely on.
  CHECK(max_distance(threejs_positions(as_written(a)), joint_positions(a)) <= kSamePlace * h);
}

TEST_CASE("real Bandai takes: the rotations layout is the default, and every reader agrees on it",
          "[export][layout]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  int files = 0;
  for (const std::string& path : test::shared_motions()) {
    if (std::filesystem::path(path).filename().string().rfind("bandai_", 0) != 0) continue;
    INFO(path);
    ++files;
    const Clip a = read_bvh_file(path);
    const double h = height_of(a);
    const Eigen::MatrixXd ours = joint_positions(a);
    // Their constant channels vary by 1e-11 cm; the trajectory is on Hips below joint_Root.
    CHECK(constant_offsets_below_root(a));
    CHECK(default_channel_layout(a) == ChannelLayout::kRotations);
    const Clip r = with_rotation_channels(a);
    check_rotations_layout(a, r);
    CHECK(r.skeleton.channel_count == 6 + 6 + 3 * 20);
    CHECK(r.skeleton.joints[a.skeleton.find("Hips")].channels.size() == 6);
    CHECK(max_distance(joint_positions(r), ours) <= kSamePlace * h);
    const Clip written = as_written(r);
    CHECK(max_distance(joint_positions(written), ours) <= kSamePlace * h);
    CHECK(max_distance(threejs_positions(written), ours) <= kSamePlace * h);
    CHECK(max_distance(threejs_positions(as_written(a)), ours) > kReadersApart * h);
  }
  CHECK(files == 7);
}

TEST_CASE("the default is as-source when a position channel below the root changes", "[export][layout]") {
  const Rig rig = make_rig();
  Clip a = make_motion(rig, 40, 3);
  // The hips' changing channels are the trajectory, not a stretching bone.
  CHECK(constant_offsets_below_root(a));
  CHECK(default_channel_layout(a) == ChannelLayout::kRotations);

  const int spine_x = rig.skeleton.joints[rig.spine].first_channel;  // Xposition
  SECTION("within the tolerance a channel still keeps one value") {
    a.motion(7, spine_x) += 1e-9 * 94.0;
    CHECK(constant_offsets_below_root(a));
    CHECK(default_channel_layout(a) == ChannelLayout::kRotations);
    CHECK_FALSE(constant_offsets_below_root(a, 0.0));
  }
  SECTION("a stretching spine") {
    a.motion(7, spine_x) += 0.5;
    CHECK_FALSE(constant_offsets_below_root(a));
    CHECK(default_channel_layout(a) == ChannelLayout::kAsSource);
  }
  SECTION("a NaN counts as a change") {
    a.motion(7, spine_x) = std::nan("");
    CHECK_FALSE(constant_offsets_below_root(a));
  }
  SECTION("the toes' single position channel") {
    const Joint& toes = rig.skeleton.joints[rig.toes];
    a.motion(a.frames() - 1, toes.first_channel) += 1.0;
    CHECK_FALSE(constant_offsets_below_root(a));
    CHECK(default_channel_layout(a) == ChannelLayout::kAsSource);
  }
  SECTION("no frames: nothing changes") {
    a.motion.resize(0, a.skeleton.channel_count);
    CHECK(constant_offsets_below_root(a));
    const Clip r = with_rotation_channels(a);
    CHECK(r.frames() == 0);
    CHECK(r.skeleton.joints[rig.spine].offset == rig.skeleton.joints[rig.spine].offset);
  }
}

TEST_CASE("with_rotation_channels refuses a position channel that changes, naming the joint", "[export][layout]") {
  const Rig rig = make_rig();
  Clip a = make_motion(rig, 40, 5);
  a.motion(7, rig.skeleton.joints[rig.spine].first_channel) += 0.5;
  CHECK_THROWS_AS(with_rotation_channels(a), InputError);
  CHECK_THROWS_WITH(with_rotation_channels(a), Catch::Contains("bandai_like.bvh") && Catch::Contains("'Spine'") &&
                                                   Catch::Contains("Xposition") && Catch::Contains("frame 8") &&
                                                   Catch::Contains("as-source"));
}

TEST_CASE("only one child of the root carries the trajectory", "[export][layout]") {
  Skeleton s;
  add_joint(s, "Root", -1, {0, 0, 0}, kPosZxy);
  add_joint(s, "Body", 0, {0, 90, 0}, kPosZxy);
  add_end_site(s, 1, {0, 10, 0});
  add_joint(s, "Prop", 0, {30, 0, 0}, kPosZxy);
  add_end_site(s, 3, {0, 5, 0});
  Clip a;
  a.source = "two_movers.bvh";
  a.skeleton = s;
  a.motion = MotionMatrix::Zero(10, s.channel_count);
  for (int f = 0; f < a.frames(); ++f) {
    a.motion(f, s.joints[1].first_channel + 1) = 90.0;
    a.motion(f, s.joints[1].first_channel + 2) = 2.0 * f;  // Body walks
    a.motion(f, s.joints[3].first_channel) = 30.0;
  }
  CHECK(constant_offsets_below_root(a));
  const Clip r = with_rotation_channels(a);
  CHECK(r.skeleton.joints[1].channels.size() == 6);
  CHECK(r.skeleton.joints[3].channels.size() == 3);
  CHECK(r.skeleton.joints[3].offset == Eigen::Vector3d(30, 0, 0));
  CHECK(max_distance(threejs_positions(as_written(r)), joint_positions(a)) <= kSamePlace * 100.0);

  for (int f = 0; f < a.frames(); ++f) a.motion(f, s.joints[3].first_channel + 2) = -1.0 * f;  // Prop moves too
  CHECK_FALSE(constant_offsets_below_root(a));
  CHECK(default_channel_layout(a) == ChannelLayout::kAsSource);
  CHECK_THROWS_WITH(with_rotation_channels(a), Catch::Contains("'Prop'") && Catch::Contains("'Body'"));
}

TEST_CASE("export_blend_bvh writes the layout asked for, A's by default", "[export][layout]") {
  const Rig rig = make_rig();
  const Clip a = make_motion(rig, 30, 13);
  const double h = height_of(a);
  const Eigen::MatrixXd all = joint_positions(a);
  Eigen::MatrixXd targets(all.rows(), 3 * static_cast<Eigen::Index>(rig.majors.size()));
  for (size_t c = 0; c < rig.majors.size(); ++c) targets.middleCols(3 * c, 3) = all.middleCols(3 * rig.majors[c], 3);
  Eigen::VectorXd at(a.frames());
  for (int f = 0; f < a.frames(); ++f) at[f] = f;
  const std::string path = (std::filesystem::temp_directory_path() / "mostyle_channel_layout_test.bvh").string();

  const ExportResult as_source = export_blend_bvh(a, rig.majors, targets, at, a.fps(), path);
  const Clip back_source = read_bvh_file(path);
  CHECK(back_source.skeleton.channel_count == a.skeleton.channel_count);
  CHECK(as_source.fit.max <= kFit * h);

  const ExportResult rotations =
      export_blend_bvh(a, rig.majors, targets, at, a.fps(), path, ChannelLayout::kRotations);
  const Clip back = read_bvh_file(path);
  CHECK(rotations.fit.max <= kFit * h);
  CHECK(back.skeleton.channel_count == rotations.clip.skeleton.channel_count);
  CHECK(back.skeleton.channel_count == 6 + 6 + 3 * (a.skeleton.joint_count_without_end_sites() - 2));
  // The same motion as the as-source file, by our reading and by three.js's.
  const Eigen::MatrixXd exported = joint_positions(back_source);
  CHECK(max_distance(joint_positions(back), exported) <= kSamePlace * h);
  CHECK(max_distance(threejs_positions(back), exported) <= kSamePlace * h);
  CHECK(max_distance(threejs_positions(back_source), exported) > kReadersApart * h);
  std::remove(path.c_str());
}
