#include "engine/io/gltf/gltf_write.h"

#include <catch2/catch.hpp>
#include <cmath>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "engine/io/bvh/bvh_read.h"
#include "engine/base/error.h"
#include "engine/io/gltf/gltf_read.h"
#include "engine/io/motion_file.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/units.h"
#include "tests/engine/io/gltf/gltf_validator.h"
#include "tests/engine/io/temp_dir.h"
#include "tests/test_data.h"

namespace fs = std::filesystem;
using namespace mostyle;
using Catch::Matchers::Contains;

namespace {

using test::TempDir;
// float32 storage: a round trip keeps positions to about 1e-7 of the height.
constexpr double kRoundTrip = 1e-5;

// Largest distance between the two clips' joints (End Sites too, matched by their place in the
// skeleton: their names are their own), frame by frame, as a fraction of a's height: no fit.
// b is in metres (glTF's unit), a in its own units, `metres` each.
double position_error(const Clip& a, const Clip& b, double metres) {
  REQUIRE(b.skeleton.joints.size() == a.skeleton.joints.size());
  const Eigen::MatrixXd pa = metres * joint_positions(a), pb = joint_positions(b);
  double worst = 0;
  for (int i = 0; i < static_cast<int>(a.skeleton.joints.size()); ++i) {
    CHECK(b.skeleton.joints[i].name == a.skeleton.joints[i].name);
    CHECK(b.skeleton.joints[i].end_site == a.skeleton.joints[i].end_site);
    for (Eigen::Index f = 0; f < std::min(pa.rows(), pb.rows()); ++f)
      worst = std::max(worst, (pa.block<1, 3>(f, 3 * i) - pb.block<1, 3>(f, 3 * i)).norm());
  }
  return worst / (metres * guess_units(a).height);
}

// The CMU walk in assets/: CMU units of 1/0.45 inch.
constexpr double kCmuMetres = 0.0254 / 0.45;

}  // namespace

TEST_CASE("glTF: BVH -> GLB -> read back is the same motion in metres, End Sites too, and the validator finds nothing",
          "[gltf]") {
  TempDir tmp;
  const Clip bvh = read_bvh_file(test::asset("motions/cmu142_walk_clumsy.bvh"));
  REQUIRE(metres_per_unit(bvh) == Approx(kCmuMetres));
  const std::string glb = tmp.path("walk.glb");
  write_gltf_file(bvh, glb);
  const AnimatedScene scene = read_gltf_file(glb);
  REQUIRE(scene.takes.size() == 1);
  CHECK(scene.takes[0].name == "walk");
  const Clip back = scene_take_to_clip(scene, 0);
  CHECK(back.frames() == bvh.frames());
  CHECK(back.fps() == bvh.fps());
  CHECK(back.skeleton.metres_per_unit == 1.0);
  CHECK(metres_per_unit(back) == 1.0);
  // The same joints and End Sites, each at the source's place in metres.
  CHECK(back.skeleton.joint_count_without_end_sites() == bvh.skeleton.joint_count_without_end_sites());
  CHECK(position_error(bvh, back, kCmuMetres) < kRoundTrip);
  // About 1.6 m tall, as a person stands (the source: 29 CMU units).
  CHECK(guess_units(back).height == Approx(kCmuMetres * guess_units(bvh).height));
  CHECK(guess_units(back).name == "metres");
  MOSTYLE_CHECK_GLTF_VALID(glb);

  // .gltf with its .bin beside it.
  const std::string gltf = tmp.path("walk text.gltf");
  write_gltf_file(bvh, gltf);
  CHECK(fs::exists(tmp.path("walk text.bin")));
  const Clip back2 = read_motion_file(gltf);
  CHECK(position_error(bvh, back2, kCmuMetres) < kRoundTrip);
  MOSTYLE_CHECK_GLTF_VALID(gltf);

  // Read back and written as BVH: the BVH is in metres, the same motion; written as glTF again,
  // nothing is scaled twice (the unit is the glTF's, stated, not guessed).
  const std::string bvh_again = tmp.path("again.bvh");
  write_motion_file(back, bvh_again);
  const Clip metres_bvh = read_bvh_file(bvh_again);
  CHECK(metres_bvh.skeleton.joints.size() == bvh.skeleton.joints.size());
  CHECK(position_error(bvh, metres_bvh, kCmuMetres) < kRoundTrip);
  const std::string glb_again = tmp.path("again.glb");
  write_gltf_file(back, glb_again);
  CHECK(position_error(bvh, read_motion_file(glb_again), kCmuMetres) < kRoundTrip);
}

TEST_CASE("glTF: lengths are written in metres whatever the source's unit", "[gltf][write]") {
  const Clip cmu = read_bvh_file(test::asset("motions/cmu142_walk_clumsy.bvh"));
  struct Case {
    const char* what;
    double units_per_cmu;  // the CMU walk's lengths times this
    double metres;         // one unit of the scaled walk in metres
  };
  // The same walk in centimetres, inches and metres, and one whose size names no unit (0.1 m of
  // a person): written as they are.
  for (const Case& c : {Case{"centimetres", 100 * kCmuMetres, 0.01}, Case{"inches", kCmuMetres / 0.0254, 0.0254},
                        Case{"metres", kCmuMetres, 1.0}, Case{"no unit", 0.06 * kCmuMetres, 1.0}}) {
    INFO(c.what);
    Clip clip = cmu;
    for (Joint& j : clip.skeleton.joints) j.offset *= c.units_per_cmu;
    for (const Joint& j : clip.skeleton.joints)
      for (size_t k = 0; k < j.channels.size(); ++k)
        if (is_position(j.channels[k])) clip.motion.col(j.first_channel + static_cast<int>(k)) *= c.units_per_cmu;
    const Clip back = scene_take_to_clip(parse_gltf(format_glb(clip, "walk"), "walk.glb"), 0);
    const double height = guess_units(back).height;
    CHECK(height == Approx(c.metres * guess_units(clip).height).epsilon(1e-6));
    CHECK(position_error(clip, back, c.metres) < kRoundTrip);
  }
  // A unit the file stated wins over the size's guess: a 1.6-unit walk in centimetres stays so.
  Clip stated = cmu;
  stated.skeleton.metres_per_unit = 0.01;
  const Clip back = scene_take_to_clip(parse_gltf(format_glb(stated, "walk"), "walk.glb"), 0);
  CHECK(position_error(stated, back, 0.01) < kRoundTrip);
}

TEST_CASE("glTF: the skeleton is written as one armature node and a skin of every joint, End Sites too", "[gltf]") {
  TempDir tmp;
  const Clip bvh = read_bvh_file(test::asset("motions/cmu142_walk_clumsy.bvh"));
  const int joints = static_cast<int>(bvh.skeleton.joints.size());
  std::string bin;
  const nlohmann::json doc = nlohmann::json::parse(format_gltf(bvh, "walk", "walk.bin", &bin));
  REQUIRE(doc["nodes"].size() == static_cast<size_t>(joints + 1));
  const nlohmann::json& armature = doc["nodes"][joints];
  CHECK(armature["name"] == "walk");
  CHECK_FALSE(armature.contains("translation"));
  CHECK(armature["children"] == nlohmann::json::array({0}));
  CHECK(doc["scenes"][0]["nodes"] == nlohmann::json::array({joints}));
  REQUIRE(doc["skins"].size() == 1);
  const nlohmann::json& skin = doc["skins"][0];
  CHECK(skin["skeleton"] == joints);
  // End Sites are bones too (Blender makes Empties of nodes outside a skin); no animation keys
  // them, so a reader takes them back as End Sites.
  std::vector<int> bones;
  for (int j = 0; j < joints; ++j) bones.push_back(j);
  CHECK(skin["joints"] == nlohmann::json(bones));
  for (const nlohmann::json& channel : doc["animations"][0]["channels"])
    CHECK_FALSE(bvh.skeleton.joints[channel["target"]["node"].get<int>()].end_site);
  // The inverse bind matrices undo each joint's rest position (translations only), in metres.
  const nlohmann::json& ibm = doc["accessors"][skin["inverseBindMatrices"].get<int>()];
  CHECK(ibm["type"] == "MAT4");
  CHECK(ibm["count"] == bones.size());
  const nlohmann::json& view = doc["bufferViews"][ibm["bufferView"].get<int>()];
  for (size_t b = 0; b < bones.size(); ++b) {
    const int j = bones[b];
    float m[16];
    std::memcpy(m, bin.data() + view["byteOffset"].get<size_t>() + 64 * b, 64);
    // Frame 0's position channels place the root; the other joints' offsets are the BVH's.
    Eigen::Vector3d world = Eigen::Vector3d::Zero();
    const MotionMatrix frame0 = bvh.motion.topRows(1);
    for (int k = j; k >= 0; k = bvh.skeleton.joints[k].parent)
      world += joint_local_translation(bvh.skeleton.joints[k], frame0.data());
    CHECK(m[0] == 1.0f);
    CHECK(m[15] == 1.0f);
    CHECK(m[12] == Approx(-kCmuMetres * world.x()).margin(1e-5));
    CHECK(m[13] == Approx(-kCmuMetres * world.y()).margin(1e-5));
    CHECK(m[14] == Approx(-kCmuMetres * world.z()).margin(1e-5));
  }
  CHECK_FALSE(doc.contains("meshes"));

  // With the stick figure: a mesh skinned to the bones on a second root, still valid.
  GltfWriteOptions o;
  o.bone_mesh = true;
  const std::string glb = tmp.path("sticks.glb");
  write_gltf_file(bvh, glb, o);
  const nlohmann::json with = nlohmann::json::parse(format_gltf(bvh, "walk", "walk.bin", &bin, o));
  REQUIRE(with["meshes"].size() == 1);
  CHECK(with["nodes"][joints + 1]["skin"] == 0);
  CHECK(with["nodes"][joints + 1]["mesh"] == 0);
  CHECK(with["scenes"][0]["nodes"] == nlohmann::json::array({joints, joints + 1}));
  MOSTYLE_CHECK_GLTF_VALID(glb);
  const Clip back = read_motion_file(glb);
  CHECK(position_error(bvh, back, kCmuMetres) < kRoundTrip);
}

TEST_CASE("glTF write: a joint name that is not UTF-8 is refused in one whole sentence", "[gltf][write][errors]") {
  Clip clip = read_bvh_file(test::asset("motions/cmu142_walk_clumsy.bvh"));
  clip.source = "walk.bvh";
  // A NUL and a byte no UTF-8 text holds: shown as \x00 and \xe8, so the message is not cut at
  // the NUL and stays one line of text.
  clip.skeleton.joints[3].name = std::string("Foot\0\xe8\n", 7);
  const std::string expected = "walk.bvh: joint name 'Foot\\x00\\xe8\\x0a' is not UTF-8 text, which glTF's names "
                               "must be; rename it to write glTF";
  CHECK_THROWS_WITH(format_glb(clip, "walk"), expected);
}
