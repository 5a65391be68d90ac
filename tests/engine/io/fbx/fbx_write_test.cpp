#include "engine/io/fbx/fbx_write.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>

#include "engine/io/bvh/bvh_read.h"
#include "engine/base/error.h"
#include "engine/io/fbx/fbx_binary.h"
#include "engine/io/fbx/fbx_read.h"
#include "engine/io/fbx/fbx_structure.h"
#include "engine/io/motion_file.h"
#include "engine/kinematics/convert.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/units.h"
#include "tests/engine/io/temp_dir.h"
#include "tests/test_data.h"

namespace fs = std::filesystem;
using namespace mostyle;
using Catch::Matchers::Contains;
using Catch::Matchers::Equals;

namespace {

// What our reader gives back of a written file, as fractions of the height. Key values are
// float32 (KeyValueFloat) and assimp composes every node's transform in float32: the mean stays
// near 1e-7 and the worst joint of a long take at 3.4e-6 (measured on a 120 fps CMU walk).
constexpr double kReadBackMean = 1e-6;
constexpr double kReadBackMax = 5e-6;

using test::TempDir;

struct ReadBack {
  double max = 0.0, mean = 0.0;  // distance between the joints of a and b / a's height
  int joints = 0;                // joints compared (a's, End Sites aside)
};

// a's joints against b's of the same name, frame by frame, no fit.
ReadBack read_back_error(const Clip& a, const Clip& b) {
  const Eigen::MatrixXd pa = joint_positions(a), pb = joint_positions(b);
  ReadBack r;
  double sum = 0;
  long count = 0;
  for (int i = 0; i < static_cast<int>(a.skeleton.joints.size()); ++i) {
    if (a.skeleton.joints[i].end_site) continue;
    const int j = b.skeleton.find(a.skeleton.joints[i].name);
    REQUIRE(j >= 0);
    ++r.joints;
    for (Eigen::Index f = 0; f < std::min(pa.rows(), pb.rows()); ++f) {
      const double d = (pa.block<1, 3>(f, 3 * i) - pb.block<1, 3>(f, 3 * j)).norm();
      r.max = std::max(r.max, d);
      sum += d;
      ++count;
    }
  }
  const double height = guess_units(a).height;
  r.max /= height;
  r.mean = count > 0 ? sum / count / height : 0.0;
  return r;
}

// Writes clip as FBX, reads it back with our reader (assimp) at the file's own rate.
Clip fbx_round_trip(const Clip& clip, const std::string& file, const FbxWriteOptions& options = {}) {
  write_fbx_file(clip, file, options);
  return read_motion_file(file);
}

void check_round_trip(const Clip& clip, const Clip& back) {
  CHECK(back.frames() == clip.frames());
  CHECK(back.fps() == clip.fps());
  const ReadBack r = read_back_error(clip, back);
  INFO(clip.source << ": " << r.joints << " joints, mean " << r.mean << ", max " << r.max << " of the height");
  CHECK(r.joints == clip.skeleton.joint_count_without_end_sites());
  CHECK(r.mean <= kReadBackMean);
  CHECK(r.max <= kReadBackMax);
}

// GlobalSettings' UnitScaleFactor in a written file: the double after its name, its type
// ("double", "Number") and an empty flags string.
double unit_scale_factor_of(const std::string& bytes) {
  const size_t at = bytes.find("UnitScaleFactor");
  REQUIRE(at != std::string::npos);
  const std::string empty_then_double("S\0\0\0\0D", 6);
  const size_t value = bytes.find(empty_then_double, at);
  REQUIRE(value != std::string::npos);
  double v = 0;
  std::memcpy(&v, bytes.data() + value + 6, 8);
  return v;
}

// The End Sites of a and b, in skeleton order, at the same places (b's of the same index).
void check_end_sites(const Clip& a, const Clip& b) {
  REQUIRE(b.skeleton.joints.size() == a.skeleton.joints.size());
  const Eigen::MatrixXd pa = joint_positions(a), pb = joint_positions(b);
  double worst = 0;
  for (size_t j = 0; j < a.skeleton.joints.size(); ++j) {
    CHECK(b.skeleton.joints[j].end_site == a.skeleton.joints[j].end_site);
    if (!a.skeleton.joints[j].end_site) continue;
    for (Eigen::Index f = 0; f < std::min(pa.rows(), pb.rows()); ++f)
      worst = std::max(worst, (pa.block<1, 3>(f, 3 * j) - pb.block<1, 3>(f, 3 * j)).norm());
  }
  CHECK(worst / guess_units(a).height <= kReadBackMax);
}

}  // namespace

TEST_CASE("FBX write: BVH -> FBX -> our reader gives the same joint positions, 7400 and 7500", "[fbx][write]") {
  TempDir tmp;
  const Clip bvh = read_bvh_file(test::asset("motions/cmu142_walk_clumsy.bvh"));
  for (const int version : {7400, 7500}) {
    for (const bool compress : {true, false}) {
      INFO("version " << version << (compress ? ", compressed" : ", plain"));
      FbxWriteOptions o;
      o.version = version;
      o.compress = compress;
      const std::string file = tmp.path("walk" + std::to_string(version) + (compress ? "z" : "") + ".fbx");
      const Clip back = fbx_round_trip(bvh, file, o);
      check_round_trip(bvh, back);
      // The End Sites are LimbNodes no curve keys: they come back as End Sites.
      check_end_sites(bvh, back);
      const std::vector<TakeInfo> takes = read_motion_takes(file);
      REQUIRE(takes.size() == 1);
      CHECK(takes[0].name == fs::path(file).stem().string());
    }
  }
}

TEST_CASE("FBX write: every Euler order is written as the joint's RotationOrder and read back", "[fbx][write]") {
  TempDir tmp;
  const Clip bvh = read_bvh_file(test::asset("motions/cmu142_walk_joy.bvh"));
  for (const EulerOrder order : {EulerOrder::kXYZ, EulerOrder::kXZY, EulerOrder::kYXZ, EulerOrder::kYZX,
                                 EulerOrder::kZXY, EulerOrder::kZYX}) {
    INFO(euler_order_name(order));
    const Clip clip = convert_euler_order(bvh, order);
    check_round_trip(clip, fbx_round_trip(clip, tmp.path("order.fbx")));
  }
}

TEST_CASE("FBX write: a joint with fewer rotation channels and a bone whose length changes", "[fbx][write]") {
  TempDir tmp;
  Clip clip;
  clip.source = "made.bvh";
  clip.frame_time = 1.0 / 24.0;
  Skeleton& s = clip.skeleton;
  s.joints.resize(4);
  s.joints[0] = {"root", -1, Eigen::Vector3d::Zero(),
                 {Channel::kXposition, Channel::kYposition, Channel::kZposition, Channel::kYrotation,
                  Channel::kXrotation, Channel::kZrotation}, 0};
  s.joints[1] = {"knee", 0, Eigen::Vector3d(0, -40, 0), {Channel::kXrotation}, 6};           // one axis
  s.joints[2] = {"slide", 1, Eigen::Vector3d(0, -40, 0),
                 {Channel::kYposition, Channel::kZrotation, Channel::kXrotation}, 7};        // two axes, moves
  s.joints[3] = {"slide End Site", 2, Eigen::Vector3d(0, -10, 0), {}, 10, true};
  s.channel_count = 10;
  const int frames = 25;
  clip.motion.resize(frames, 10);
  for (int f = 0; f < frames; ++f) {
    const double t = f / 24.0;
    clip.motion.row(f) << 10 * t, 90 + std::sin(t), 30 * t, 200 * t, 20 * std::sin(3 * t), 170 + 30 * t,  //
        80 * std::sin(2 * t), -40 - 5 * t, 60 * t, -45 * t;
  }
  check_round_trip(clip, fbx_round_trip(clip, tmp.path("made.fbx")));
  // 24 fps is an FBX rate of its own.
  CHECK(scan_fbx_structure(format_fbx(clip, "made")).models.size() == 5);  // the armature and 4 joints
}

TEST_CASE("FBX write: the binary layout: header, records, models and their parents, footer", "[fbx][write]") {
  const Clip bvh = read_bvh_file(test::asset("motions/cmu142_walk_clumsy.bvh"));
  for (const int version : {7400, 7500}) {
    FbxWriteOptions o;
    o.version = version;
    const std::string bytes = format_fbx(bvh, "walk", o);
    REQUIRE(bytes.size() > 200);
    CHECK(bytes.substr(0, 23) == std::string("Kaydara FBX Binary  \0\x1a\0", 23));
    uint32_t stored = 0;
    std::memcpy(&stored, bytes.data() + 23, 4);
    CHECK(stored == static_cast<uint32_t>(version));
    // The footer ends with the version, 120 zero bytes and 16 bytes of magic.
    std::memcpy(&stored, bytes.data() + bytes.size() - 140, 4);
    CHECK(stored == static_cast<uint32_t>(version));
    CHECK(bytes.substr(bytes.size() - 136, 120) == std::string(120, '\0'));
    CHECK(bytes.substr(bytes.size() - 16) == "\xf8\x5a\x8c\x6a\xde\xf5\xd9\x7e\xec\xe9\x0c\xe3\x75\x8f\x29\x0b");
    CHECK((bytes.size() - 140) % 16 == 0);  // the footer's padding aligns the version's block
    const FbxStructure structure = scan_fbx_structure(bytes);
    CHECK(structure.models.size() == bvh.skeleton.joints.size() + 1);
    CHECK(structure.record_depth >= 4);  // Objects > Model > Properties70 > P
    // Every joint's chain reaches the armature: skeleton depth + 1 models, no loop.
    int deepest = 0;
    for (size_t j = 0; j < bvh.skeleton.joints.size(); ++j) {
      int depth = 1;
      for (int p = bvh.skeleton.joints[j].parent; p >= 0; p = bvh.skeleton.joints[p].parent) ++depth;
      deepest = std::max(deepest, depth);
    }
    CHECK(longest_model_chain(structure) == deepest + 1);
    // The same clip gives the same bytes.
    CHECK(format_fbx(bvh, "walk", o) == bytes);
  }
}

TEST_CASE("FBX write: time modes: the FBX rates by their codes, others custom", "[fbx][write]") {
  CHECK(fbx_time_mode(120) == 1);
  CHECK(fbx_time_mode(100) == 2);
  CHECK(fbx_time_mode(60) == 3);
  CHECK(fbx_time_mode(30) == 6);
  CHECK(fbx_time_mode(25) == 10);
  CHECK(fbx_time_mode(24) == 11);
  CHECK(fbx_time_mode(29.97) == 14);
  CHECK(fbx_time_mode(90) == 14);
  // A custom rate: assimp reads CustomFrameRate, the keys land on its frames.
  TempDir tmp;
  Clip bvh = read_bvh_file(test::asset("motions/cmu142_walk_clumsy.bvh"));
  bvh.frame_time = 1.0 / 90.0;
  check_round_trip(bvh, fbx_round_trip(bvh, tmp.path("ninety.fbx")));
}

TEST_CASE("FBX write: what cannot be written is one sentence naming the clip", "[fbx][write][errors]") {
  Clip empty;
  empty.source = "empty.bvh";
  CHECK_THROWS_WITH(format_fbx(empty, "x"), Contains("empty.bvh: has no joints"));
  Clip clip = read_bvh_file(test::asset("motions/cmu142_walk_clumsy.bvh"));
  clip.source = "walk.bvh";
  Clip still = clip;
  still.motion.resize(0, clip.skeleton.channel_count);
  CHECK_THROWS_WITH(format_fbx(still, "x"), Contains("walk.bvh: has no frames"));
  Clip named = clip;
  named.skeleton.joints[1].name = std::string("a\0b", 3);
  CHECK_THROWS_WITH(format_fbx(named, "x"), Contains("walk.bvh: joint name 'a\\x00b' holds a NUL byte"));
  // Two joints of one name: a reader would give both names' curves to one of them.
  Clip twice = clip;
  twice.skeleton.joints[2].name = twice.skeleton.joints[1].name;
  CHECK_THROWS_WITH(format_fbx(twice, "x"),
                    Equals("walk.bvh: two joints are named '" + clip.skeleton.joints[1].name +
                           "', and FBX readers tell joints apart by name; rename one to write FBX"));
  FbxWriteOptions old;
  old.version = 6100;
  CHECK_THROWS_WITH(format_fbx(clip, "x", old), Contains("walk.bvh: FBX version 6100 is not written"));
}

TEST_CASE("FBX write: the shared Bandai (30 fps), CMU (120 fps) and Aalto (100 fps) takes read back", "[fbx][write][shared]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  TempDir tmp;
  for (const char* name : {"bandai_walk_normal.bvh", "cmu142_walk_happy.bvh", "wild/aalto_k_walk_slow.bvh"}) {
    const Clip bvh = read_bvh_file(test::shared_motion(name));
    const Clip back = fbx_round_trip(bvh, tmp.path("take.fbx"));
    check_round_trip(bvh, back);
    const ReadBack r = read_back_error(bvh, back);
    WARN(name << " -> FBX -> read back: mean " << r.mean << ", max " << r.max << " of the height");
  }
}

TEST_CASE("FBX write: UnitScaleFactor is the unit the source states, else the one its size suggests",
          "[fbx][write]") {
  Clip clip = read_bvh_file(test::asset("motions/cmu142_walk_clumsy.bvh"));
  CHECK(unit_scale_factor_of(format_fbx(clip, "walk")) == Approx(2.54 / 0.45));  // CMU units by their size
  // The same skeleton read from glTF, whose unit is the metre: 100, whatever its size suggests.
  clip.skeleton.metres_per_unit = 1.0;
  CHECK(unit_scale_factor_of(format_fbx(clip, "walk")) == 100.0);
  // Nothing tells: FBX's own centimetre.
  clip.skeleton.metres_per_unit = 0.0;
  for (Joint& j : clip.skeleton.joints) j.offset *= 400.0;
  for (const Joint& j : clip.skeleton.joints)
    for (size_t k = 0; k < j.channels.size(); ++k)
      if (is_position(j.channels[k])) clip.motion.col(j.first_channel + static_cast<int>(k)) *= 400.0;
  REQUIRE(guess_units(clip).name == "unknown");
  CHECK(unit_scale_factor_of(format_fbx(clip, "walk")) == 1.0);
}

TEST_CASE("FBX: Mixamo's end bones are read and written, 61 joints and 15 end bones", "[fbx][write][shared]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  TempDir tmp;
  // The file has no mesh: its skeleton is the animated LimbNodes and the ones that hang from
  // them (HeadTop_End, the fingers' 4th bones, Toe_End, Hair_End, Cloak_End), as Blender reads it.
  const Clip mixamo = read_motion_file(test::shared_motion("wild/fbx_mixamo_walking.fbx"));
  CHECK(mixamo.skeleton.joints.size() == 76);
  CHECK(mixamo.skeleton.joint_count_without_end_sites() == 61);
  const int head_top = static_cast<int>(std::find_if(mixamo.skeleton.joints.begin(), mixamo.skeleton.joints.end(),
                                                     [](const Joint& j) { return j.name == "mixamorig:HeadTop_End"; }) -
                                        mixamo.skeleton.joints.begin());
  REQUIRE(head_top < 76);
  CHECK(mixamo.skeleton.joints[head_top].end_site);
  for (const char* ext : {".fbx", ".glb"}) {
    INFO(ext);
    const std::string file = tmp.path(std::string("walking") + ext);
    write_motion_file(mixamo, file);
    const Clip back = read_motion_file(file);
    CHECK(back.skeleton.joints.size() == 76);
    CHECK(back.skeleton.joint_count_without_end_sites() == 61);
  }
}
