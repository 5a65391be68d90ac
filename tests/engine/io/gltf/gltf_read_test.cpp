#include "engine/io/gltf/gltf_read.h"
#include "engine/io/gltf/gltf_write.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>

#include <nlohmann/json.hpp>

#include "engine/io/bvh/bvh_read.h"
#include "engine/base/error.h"
#include "engine/io/motion_file.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/resample.h"
#include "tests/engine/io/motion_compare.h"
#include "tests/engine/io/temp_dir.h"
#include "tests/test_data.h"

using namespace mostyle;
using Catch::Matchers::Contains;

namespace {

using test::TempDir;
using test::kMaxBound;
using test::kMeanBound;

std::string floats(std::initializer_list<float> values) {
  std::string out(values.size() * 4, '\0');
  std::memcpy(out.data(), values.begin(), out.size());
  return out;
}

}  // namespace

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
