// The BVH writer: what it writes reads back bit for bit, laid out as the standard is, and
// atomically.
#include "engine/io/bvh/bvh_write.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

#include "engine/base/error.h"
#include "engine/io/bvh/bvh_read.h"
#include "engine/kinematics/kinematics.h"
#include "tests/engine/io/bvh/bvh_checks.h"
#include "tests/engine/small_bvh.h"
#include "tests/test_data.h"

using namespace mostyle;
namespace fs = std::filesystem;

namespace {

using test::check_same_clip;
using test::replace_all;
const std::string& kSmall = test::kSmallBvh;                                                     // 20

std::string temp_dir() {
  const fs::path dir = fs::temp_directory_path() / ("mostyle_bvh_write_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir.string();
}

}  // namespace

TEST_CASE("write/read round trip: bit-exact values, same FK", "[bvh]") {
  std::vector<std::string> files = test::asset_motions();
  for (const std::string& f : test::shared_motions()) files.push_back(f);
  for (const std::string& path : files) {
    INFO(path);
    const Clip clip = read_bvh_file(path);
    const std::string text = format_bvh(clip);
    std::vector<std::string> warnings;
    const Clip back = parse_bvh(text, "back.bvh", &warnings);
    CHECK(warnings.empty());
    CHECK(back.motion == clip.motion);  // shortest round-trip numbers: every bit
    CHECK(back.frame_time == clip.frame_time);
    REQUIRE(back.skeleton.joints.size() == clip.skeleton.joints.size());
    for (size_t i = 0; i < clip.skeleton.joints.size(); ++i) {
      CHECK(back.skeleton.joints[i].name == clip.skeleton.joints[i].name);
      CHECK(back.skeleton.joints[i].channels == clip.skeleton.joints[i].channels);
      CHECK(back.skeleton.joints[i].parent == clip.skeleton.joints[i].parent);
    }
    CHECK(joint_positions(back) == joint_positions(clip));
    // Formatting is a fixed point.
    CHECK(format_bvh(back) == text);
  }
}

TEST_CASE("the writer: standard layout, shortest numbers, LF, root OFFSET zeroed", "[bvh]") {
  Clip clip = parse_bvh(replace_all(kSmall, "OFFSET 0 0 0", "OFFSET 7 8 9"), "w.bvh");
  clip.motion(0, 0) = 0.1;
  clip.motion(0, 1) = 1.0 / 3;
  clip.motion(0, 2) = -0.0;
  clip.motion(0, 3) = 1e-7;
  const std::string text = format_bvh(clip);
  CHECK(text.find('\r') == std::string::npos);
  CHECK(text.rfind("HIERARCHY\nROOT Hips\n{\n\tOFFSET 0 0 0\n\tCHANNELS 6 Xposition", 0) == 0);
  CHECK(text.find("\tJOINT Spine\n\t{\n\t\tOFFSET 0 10 0\n\t\tCHANNELS 3 Zrotation Xrotation Yrotation\n"
                  "\t\tEnd Site\n\t\t{\n\t\t\tOFFSET 0 5 0\n\t\t}\n\t}\n}\nMOTION\nFrames: 2\n"
                  "Frame Time: 0.0333333\n0.1 0.3333333333333333 -0 1e-07 0 0 0 0 0\n") !=
        std::string::npos);
  // The root's OFFSET was moot (its position channels place it): FK is unchanged.
  CHECK(joint_positions(parse_bvh(text, "r.bvh")) == joint_positions(clip));
}

TEST_CASE("three.js reads the written root the same (it adds OFFSET to position channels)", "[bvh]") {
  // three.js's BVHLoader animates every bone's position as OFFSET + position channels (0 when
  // absent). With the root OFFSET written as 0 that equals our (Blender's) root position.
  Clip clip = read_bvh_file(test::asset("motions/cmu142_walk_marching.bvh"));
  clip.skeleton.joints[0].offset = Eigen::Vector3d(1, 2, 3);  // a file with a root OFFSET
  const Clip back = parse_bvh(format_bvh(clip), "w.bvh");
  const Eigen::MatrixXd p = joint_positions(clip);
  for (int f = 0; f < clip.frames(); f += 100) {
    const Eigen::Vector3d three_js = back.skeleton.joints[0].offset + back.motion.row(f).head<3>().transpose();
    CHECK(three_js == p.block<1, 3>(f, 0).transpose());
  }
}

TEST_CASE("write_bvh_file writes atomically and leaves nothing on failure", "[bvh]") {
  const std::string dir = temp_dir();
  const Clip clip = parse_bvh(kSmall, "x.bvh");
  const std::string path = dir + "/out.bvh";
  write_bvh_file(clip, path);
  check_same_clip(read_bvh_file(path), clip);
  // Overwrite: the new content replaces the old one.
  Clip other = clip;
  other.motion(0, 0) = 42;
  write_bvh_file(other, path);
  CHECK(read_bvh_file(path).motion(0, 0) == 42);
  // A folder that does not exist: InputError naming the path, and no file at all.
  const std::string missing = dir + "/no/such/folder/out.bvh";
  CHECK_THROWS_WITH(write_bvh_file(clip, missing), Catch::StartsWith(missing + ": cannot write: "));
  CHECK_FALSE(fs::exists(missing));
  // Writing over a folder fails and removes its temporary file.
  fs::create_directories(dir + "/a_folder.bvh");
  CHECK_THROWS_AS(write_bvh_file(clip, dir + "/a_folder.bvh"), InputError);
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += e.path().filename() != "a_folder.bvh";
  CHECK(entries == 1);  // only out.bvh: no temporary left behind
  // Reading a missing file or a folder: InputError naming it.
  CHECK_THROWS_WITH(read_bvh_file(dir + "/none.bvh"), Catch::StartsWith(dir + "/none.bvh: cannot read: "));
  CHECK_THROWS_WITH(read_bvh_file(dir), Catch::Contains("cannot read: it is a folder"));
  fs::remove_all(dir);
}
