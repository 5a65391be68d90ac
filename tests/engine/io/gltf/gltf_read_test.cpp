#include "engine/io/gltf/gltf_read.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "engine/io/bvh/bvh_read.h"
#include "engine/base/error.h"
#include "engine/io/motion_file.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/resample.h"
#include "engine/kinematics/units.h"
#include "tests/engine/io/gltf/gltf_validator.h"
#include "tests/engine/io/motion_compare.h"
#include "tests/test_data.h"

namespace fs = std::filesystem;
using namespace mostyle;
using Catch::Matchers::Contains;

namespace {

using test::kMaxBound;
using test::kMeanBound;
// float32 storage: a round trip keeps positions to about 1e-7 of the height.
constexpr double kRoundTrip = 1e-5;

struct TempDir {
  fs::path dir = fs::temp_directory_path() / ("mostyle_gltf_test_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(dir); }
  ~TempDir() { fs::remove_all(dir); }
  std::string path(const std::string& name) const { return (dir / name).string(); }
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(dir / name, std::ios::binary) << bytes;
    return path(name);
  }
};

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

std::string floats(std::initializer_list<float> values) {
  std::string out(values.size() * 4, '\0');
  std::memcpy(out.data(), values.begin(), out.size());
  return out;
}

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

TEST_CASE("glTF: a .gltf written by hand with STEP and CUBICSPLINE samplers", "[gltf]") {
  TempDir tmp;
  // Buffer: times 0, 1 (8 bytes); STEP translations of Hips (24); CUBICSPLINE rotations of Hips,
  // 3 x 2 VEC4 (96); Spine's translation, constant (24): it moves with Hips, so it is a joint.
  const double s = std::sin(M_PI / 4), c = std::cos(M_PI / 4);
  std::string bin = floats({0.f, 1.f});
  bin += floats({0, 0, 0, 0, 10, 0});
  bin += floats({0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0,  //
                 0, 0, 0, 0, 0, 0, float(s), float(c), 0, 0, 0, 0});
  bin += floats({0, 1, 0, 0, 1, 0});
  tmp.write("hand.bin", bin);
  const std::string json = R"({
    "asset": {"version": "2.0"},
    "nodes": [{"name": "Hips", "children": [1]}, {"name": "Spine", "translation": [0, 1, 0]},
              {"name": "Camera"}],
    "buffers": [{"uri": "hand.bin", "byteLength": 152}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 8},
                    {"buffer": 0, "byteOffset": 8, "byteLength": 24},
                    {"buffer": 0, "byteOffset": 32, "byteLength": 96},
                    {"buffer": 0, "byteOffset": 128, "byteLength": 24}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]},
                  {"bufferView": 1, "componentType": 5126, "count": 2, "type": "VEC3"},
                  {"bufferView": 2, "componentType": 5126, "count": 6, "type": "VEC4"},
                  {"bufferView": 3, "componentType": 5126, "count": 2, "type": "VEC3"}],
    "animations": [{"name": "hop", "samplers": [
                      {"input": 0, "output": 1, "interpolation": "STEP"},
                      {"input": 0, "output": 2, "interpolation": "CUBICSPLINE"},
                      {"input": 0, "output": 3}],
                    "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}},
                                 {"sampler": 1, "target": {"node": 0, "path": "rotation"}},
                                 {"sampler": 2, "target": {"node": 1, "path": "translation"}}]}]
  })";
  const std::string file = tmp.write("hand.gltf", json);
  MotionReadOptions o;
  o.fps = 4;
  const Clip clip = read_motion_file(file + "#hop", nullptr, o);
  REQUIRE(clip.frames() == 5);
  CHECK(clip.skeleton.joints.size() == 2);  // the camera node is no joint
  const Eigen::MatrixXd p = joint_positions(clip);
  // STEP: the hips stay at 0 until t = 1.
  CHECK(p(3, 1) == 0.0);
  CHECK(p(4, 1) == Approx(10.0));
  // CUBICSPLINE with zero tangents: smoothstep from 0 to 90 degrees about Z. At t = 0.5 the
  // Hermite weights are 1/2 and 1/2: normalized, 45 degrees; Spine 1 along the turned Y.
  CHECK(p(2, 3) == Approx(-std::sin(M_PI / 4)).margin(1e-6));
  CHECK(p(2, 4) == Approx(std::cos(M_PI / 4)).margin(1e-6));
  CHECK(p(4, 3) == Approx(-1.0).margin(1e-6));
  CHECK(p(4, 4) == Approx(10.0).margin(1e-6));
}

TEST_CASE("glTF: every animation of a file reads on its one skeleton, the skin's joints", "[gltf]") {
  TempDir tmp;
  // Buffer: times 0, 1 (8 bytes); two rotation keys, none and a quarter turn about Z (32); two
  // translation keys (24).
  const float s = static_cast<float>(std::sin(M_PI / 4)), c = static_cast<float>(std::cos(M_PI / 4));
  std::string bin = floats({0.f, 1.f});
  bin += floats({0, 0, 0, 1, 0, 0, s, c});
  bin += floats({0, 1, 0, 0, 2, 0});
  tmp.write("rig.bin", bin);
  // Hips with Left and Right; Right's child RightEnd is keyed by no animation. "walk" keys the
  // hips and Left, "wave" only Right.
  const std::string nodes_and_animations = R"(
    "asset": {"version": "2.0"},
    "scenes": [{"nodes": [0]}],
    "nodes": [{"name": "Armature", "children": [1, 5]},
              {"name": "Hips", "translation": [0, 1, 0], "children": [2, 3]},
              {"name": "Left", "translation": [1, 0, 0]},
              {"name": "Right", "translation": [-1, 0, 0], "children": [4]},
              {"name": "RightEnd", "translation": [0, -1, 0]},
              {"name": "Body"}],
    "buffers": [{"uri": "rig.bin", "byteLength": 64}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 8},
                    {"buffer": 0, "byteOffset": 8, "byteLength": 32},
                    {"buffer": 0, "byteOffset": 40, "byteLength": 24}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]},
                  {"bufferView": 1, "componentType": 5126, "count": 2, "type": "VEC4"},
                  {"bufferView": 2, "componentType": 5126, "count": 2, "type": "VEC3"}],
    "animations": [{"name": "walk", "samplers": [{"input": 0, "output": 2}, {"input": 0, "output": 1}],
                    "channels": [{"sampler": 0, "target": {"node": 1, "path": "translation"}},
                                 {"sampler": 1, "target": {"node": 2, "path": "rotation"}}]},
                   {"name": "wave", "samplers": [{"input": 0, "output": 1}],
                    "channels": [{"sampler": 0, "target": {"node": 3, "path": "rotation"}}]}])";
  const auto names = [](const Clip& clip) {
    std::vector<std::string> out;
    for (const Joint& j : clip.skeleton.joints) out.push_back(j.name);
    return out;
  };
  MotionReadOptions o;
  o.fps = 10;
  SECTION("with a skin: its joints, RightEnd among them") {
    const std::string file = tmp.write("skin.gltf", "{" + nodes_and_animations + R"(,
      "skins": [{"joints": [1, 2, 3, 4]}]})");
    const Clip walk = read_motion_file(file + "#walk", nullptr, o), wave = read_motion_file(file + "#wave", nullptr, o);
    const std::vector<std::string> expected = {"Hips", "Left", "Right", "RightEnd"};
    CHECK(names(walk) == expected);
    CHECK(names(wave) == expected);
    CHECK(walk.skeleton.channel_count == wave.skeleton.channel_count);
    // In walk, Right and RightEnd keep their rest pose under the moving hips.
    const Eigen::MatrixXd p = joint_positions(walk);
    CHECK(p.row(10).segment<3>(0).isApprox(Eigen::RowVector3d(0, 2, 0)));
    CHECK(p.row(10).segment<3>(6).isApprox(Eigen::RowVector3d(-1, 2, 0)));
    CHECK(p.row(10).segment<3>(9).isApprox(Eigen::RowVector3d(-1, 1, 0)));
    // In wave, Right turns a quarter about Z: RightEnd swings from below it to its side.
    const Eigen::MatrixXd q = joint_positions(wave);
    CHECK(q.row(10).segment<3>(9).isApprox(Eigen::RowVector3d(0, 1, 0)));
    CHECK(q.row(10).segment<3>(3).isApprox(Eigen::RowVector3d(1, 1, 0)));  // Left at rest
    const std::vector<TakeInfo> takes = read_motion_takes(file);
    REQUIRE(takes.size() == 2);
    CHECK(takes[0].moves == 2);
    CHECK(takes[1].moves == 1);
  }
  SECTION("without: the nodes any animation keys") {
    const std::string file = tmp.write("bare.gltf", "{" + nodes_and_animations + "}");
    const std::vector<std::string> expected = {"Hips", "Left", "Right"};
    CHECK(names(read_motion_file(file + "#walk", nullptr, o)) == expected);
    CHECK(names(read_motion_file(file + "#wave", nullptr, o)) == expected);
  }
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

TEST_CASE("glTF: bad files are one sentence naming the file", "[gltf][errors]") {
  TempDir tmp;
  const Clip bvh = read_bvh_file(test::asset("motions/cmu142_walk_clumsy.bvh"));
  const std::string glb = format_glb(bvh, "walk");
  CHECK_THROWS_WITH(parse_gltf(glb.substr(0, glb.size() / 2), "cut.glb"), Contains("cut.glb: not a readable glTF file"));
  CHECK_THROWS_WITH(parse_gltf("garbage", "junk.gltf"), Contains("junk.gltf: not a readable glTF file"));
  CHECK_THROWS_WITH(parse_gltf(R"({"asset": {"version": "2.0"}, "nodes": [{"name": "a"}]})", "still.gltf"),
                    Contains("still.gltf: has no animation"));
  CHECK_THROWS_WITH(parse_gltf(R"({"asset": {"version": "2.0"}, "nodes": [{"children": [1]}, {"children": [0]}]})",
                               "loop.gltf"),
                    Contains("loop.gltf: "));
  const std::string deep = R"({"asset": {"version": "2.0"}, "extras": )" + std::string(5000, '[') +
                           std::string(5000, ']') + "}";
  CHECK_THROWS_WITH(parse_gltf(deep, "deep.gltf"), Contains("deep.gltf: not a readable glTF file: its JSON nests deeper"));
  CHECK_THROWS_WITH(read_motion_file(tmp.write("w.glb", glb) + "#run"), Contains("w.glb: has no animation 'run'; it has 'walk'"));
  CHECK_THROWS_WITH(read_motion_file(tmp.path("missing.glb")), Contains("missing.glb: cannot read"));
  // The memory limit holds before the frames are sampled.
  MotionReadOptions small;
  small.max_bytes = glb.size() + 1024;
  CHECK_THROWS_WITH(read_motion_file(tmp.path("w.glb"), nullptr, small), Contains("MOSTYLE_MAX_MEMORY_MB"));
}

TEST_CASE("glTF: Blender's GLB of three walks reads as the BVHs they came from", "[gltf][shared]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  const std::string file = test::shared_motion("formats/cmu142_walks_30fps.glb");
  const std::vector<TakeInfo> takes = read_motion_takes(file);
  REQUIRE(takes.size() == 3);
  CHECK(takes[0].name == "cmu142_walk_clumsy");
  std::vector<std::string> notes;
  const Clip first = read_motion_file(file, nullptr, {}, &notes);
  REQUIRE(notes.size() == 1);
  CHECK_THAT(notes[0], Contains("'cmu142_walk_happy', 'cmu142_walk_joy'"));
  CHECK(first.fps() == 30);  // from the keys' spacing
  for (const char* name : {"cmu142_walk_clumsy", "cmu142_walk_happy", "cmu142_walk_joy"}) {
    const Clip bvh = read_bvh_file(test::shared_motion(std::string(name) + ".bvh"));
    // The file's own rate (from its keys' spacing: 30) and 30 given.
    for (double fps : {0.0, 30.0}) {
      MotionReadOptions o;
      o.fps = fps;
      const Clip clip = read_motion_file(file + "#" + name, nullptr, o);
      CHECK(clip.fps() == 30.0);
      const Clip reference = resample_clip(bvh, 30.0);
      const test::MotionDifference d = test::motion_difference(reference, clip);
      INFO(name << " at " << fps << " fps: mean " << d.mean << ", max " << d.max << " of the height, "
                << d.frames << " frames, " << d.joints << " joints");
      CHECK(d.joints == 31);
      CHECK(std::abs(clip.frames() - reference.frames()) <= 1);
      CHECK(d.mean <= kMeanBound);
      CHECK(d.max <= kMaxBound);
      WARN(name << " GLB at " << fps << " fps: mean " << d.mean << ", max " << d.max);
    }
  }
}
