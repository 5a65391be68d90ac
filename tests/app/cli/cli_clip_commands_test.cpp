// mostyle-cli info | fk | convert, run as a user runs them: exit 0 ok, 1 bad input (one line on
// stderr naming file and line), 2 bad usage; a failed write leaves no file.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "engine/io/bvh/bvh_read.h"
#include "engine/io/motion_file.h"
#include "engine/kinematics/kinematics.h"
#include "tests/app/cli/cli_sandbox.h"
#include "tests/engine/io/gltf/gltf_validator.h"
#include "tests/test_data.h"

namespace fs = std::filesystem;
using namespace mostyle;

namespace {

using Run = test::CliRun;

// A scratch folder of this test file's own.
class Sandbox : public test::CliSandbox {
 public:
  Sandbox() : test::CliSandbox("mostyle_cli_test") {}
};

int lines_in(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

const std::string kBad =
    "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 3 Zrotation Xrotation Wrotation\n";

}  // namespace

TEST_CASE("cli info: text and JSON", "[cli][bvh]") {
  Sandbox box;
  const std::string file = test::asset("motions/cmu142_walk_clumsy.bvh");
  Run r = box.cli("info \"" + file + "\"");
  CHECK(r.status == 0);
  CHECK(r.err.empty());
  CHECK(r.out.find("joints: 31 (+7 End Sites)") != std::string::npos);
  CHECK(r.out.find("(120 fps)") != std::string::npos);
  CHECK(r.out.find("    LeftUpLeg  [Zrotation Yrotation Xrotation] order ZYX") != std::string::npos);
  r = box.cli("info --json \"" + file + "\"");
  CHECK(r.status == 0);
  CHECK(r.out.find("\"frames\": 1080") != std::string::npos);
  CHECK(r.out.find("\"fps\": 120.0") != std::string::npos);
  // Joint names that are not UTF-8 do not stop the JSON.
  const std::string latin1 = box.write(
      "latin1.bvh", "HIERARCHY\nROOT H\xfc" "fte\n{\nOFFSET 0 0 0\nCHANNELS 0\n}\nMOTION\nFrames: 0\nFrame Time: 0.1\n");
  r = box.cli("info --json \"" + latin1 + "\"");
  CHECK(r.status == 0);
  CHECK(r.out.find("\"name\": \"H\xef\xbf\xbd" "fte\"") != std::string::npos);
  // No major joints: no cycles to tell, said, and info still works.
  CHECK(r.out.find("\"kind\": \"unknown\"") != std::string::npos);
}

TEST_CASE("cli info: the skeleton once, the takes on it, how each major joint was found", "[cli][bvh]") {
  Sandbox box;
  const std::string file = test::asset("motions/cmu142_walk_clumsy.bvh");
  Run r = box.cli("info \"" + file + "\"");
  REQUIRE(r.status == 0);
  CHECK(r.out.find("  joints: 31 (+7 End Sites), the file's hierarchy, root 'Hips'\n") != std::string::npos);
  CHECK(r.out.find("    cmu142_walk_clumsy  (8.99") != std::string::npos);
  CHECK(r.out.find("keyframes, moves 31 joints)") != std::string::npos);
  CHECK(r.out.find("  major joints: 20 by name\n") != std::string::npos);
  CHECK(r.out.find("    left_knee: LeftLeg (name)\n") != std::string::npos);
  // A mapping file's line says so.
  const std::string mapping = box.write("chest.txt", "chest = Neck1\nleft_hand = -\n");
  r = box.cli("info --json --mapping \"" + mapping + "\" \"" + file + "\"");
  REQUIRE(r.status == 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  CHECK(j["skeleton"]["joints"] == 31);
  CHECK(j["skeleton"]["end_sites"] == 7);
  CHECK(j["skeleton"]["root"] == "Hips");
  CHECK(j["skeleton"]["from"] == "hierarchy");
  CHECK(j["takes"][0]["moves"] == 31);
  const nlohmann::json& majors = j["major_joints"];
  CHECK(majors["how"] == "18 by name, 1 from the mapping file; missing: left_hand");
  REQUIRE(majors["joints"].size() == 20);
  CHECK(majors["joints"][2] == nlohmann::json({{"role", "chest"}, {"joint", "Neck1"}, {"found_by", "mapping file"}}));
  CHECK(majors["joints"][7]["joint"].is_null());
  CHECK(majors["joints"][7]["found_by"] == "mapping file");
  CHECK(majors["joints"][0]["found_by"] == "name");
  // A bad mapping file: one line naming it, exit 1.
  const std::string bad = box.write("bad.txt", "chest = Nope\n");
  r = box.cli("info --mapping \"" + bad + "\" \"" + file + "\"");
  CHECK(r.status == 1);
  CHECK(lines_in(r.err) == 1);
  CHECK(r.err.find("bad.txt:1: expected a joint of the skeleton for chest") != std::string::npos);
}

TEST_CASE("cli info: a glTF file's one skeleton, its animations and joints found by structure",
          "[cli][gltf][shared]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  Sandbox box;
  const std::string robot = test::shared_motion("wild/gltf_godot_robot_walk_run.glb");
  Run r = box.cli("info \"" + robot + "#walk\"");
  REQUIRE(r.status == 0);
  CHECK(r.out.find("  joints: 27 (+0 End Sites), the joints of the file's skins, root 'MASTER'\n") != std::string::npos);
  CHECK(r.out.find("  takes: 8, every one on this skeleton\n") != std::string::npos);
  CHECK(r.out.find("    walk  (") != std::string::npos);
  // Its l- joints lie on its right: the body's sides win.
  CHECK(r.out.find("    left_hip: r-thigh (name)\n") != std::string::npos);
  CHECK(r.out.find("the names' left and right are swapped") != std::string::npos);
  const std::string cesium = test::shared_motion("wild/gltf_cesiumman_walk.glb");
  r = box.cli("info --json \"" + cesium + "\"");
  REQUIRE(r.status == 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  CHECK(j["skeleton"]["joints"] == 19);
  CHECK(j["skeleton"]["from"] == "skins");
  CHECK(j["takes"][0]["moves"] == 19);
  for (const auto& major : j["major_joints"]["joints"])
    CHECK(major["found_by"] == (major["joint"].is_null() ? "none" : "structure"));
  CHECK(j["major_joints"]["joints"][12]["joint"] == "leg_joint_L_1");
  CHECK(j["major_joints"]["how"].get<std::string>().find("left told by the toes in the rest pose") !=
        std::string::npos);
}

TEST_CASE("cli info and align list each take's cycles", "[cli][bvh]") {
  Sandbox box;
  const std::string walk = test::asset("motions/cmu142_walk_clumsy.bvh");
  Run r = box.cli("info --json \"" + walk + "\"");
  REQUIRE(r.status == 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const nlohmann::json& c = j["cycles"];
  CHECK(c["kind"] == "gait");
  REQUIRE(c["cycles"].size() >= 5);
  int previous_end = 0;
  for (const auto& cycle : c["cycles"]) {  // in the file's own frames (120 fps), in order
    const int start = cycle["start"], end = cycle["end"];
    CHECK(start >= previous_end);
    CHECK(end > start);
    CHECK(end <= j["frames"].get<int>());
    CHECK(cycle["seconds"].get<double>() == Approx((end - start) / 120.0));
    previous_end = end;
  }
  CHECK(c["period_s"].get<double>() > 0.6);
  CHECK(c["period_s"].get<double>() < 1.6);
  r = box.cli("info \"" + walk + "\"");
  CHECK(r.out.find("  cycles: gait, ") != std::string::npos);
  // align: both takes' cycles at the working rate.
  r = box.cli("align --json \"" + walk + "\" \"" + test::asset("motions/cmu142_walk_happy.bvh") + "\"");
  REQUIRE(r.status == 0);
  const nlohmann::json a = nlohmann::json::parse(r.out);
  CHECK(a["cycles"]["a"]["kind"] == "gait");
  CHECK(a["cycles"]["b"]["kind"] == "gait");
  CHECK(a["cycles"]["a"]["cycles"].size() >= 5);
}

TEST_CASE("cli: bad input exits 1 with one line naming file and line", "[cli][bvh]") {
  Sandbox box;
  const std::string bad = box.write("bad.bvh", kBad);
  for (const std::string& command : {"info \"" + bad + "\"", "info --json \"" + bad + "\"",
                                     "fk \"" + bad + "\" --out \"" + box.path("p.csv") + "\"",
                                     "convert \"" + bad + "\" \"" + box.path("o.bvh") + "\""}) {
    INFO(command);
    const Run r = box.cli(command);
    CHECK(r.status == 1);
    CHECK(r.out.empty());
    CHECK(r.err == "mostyle: " + bad +
                       ":5: expected a channel name (Xposition .. Zrotation) for joint 'Hips', found "
                       "'Wrotation'\n");
  }
  CHECK_FALSE(fs::exists(box.path("p.csv")));
  CHECK_FALSE(fs::exists(box.path("o.bvh")));
  const Run missing = box.cli("info \"" + box.path("none.bvh") + "\"");
  CHECK(missing.status == 1);
  CHECK(lines_in(missing.err) == 1);
  CHECK(missing.err.rfind("mostyle: " + box.path("none.bvh") + ": cannot read: ", 0) == 0);
  // A file cut short: where it ends and how many frames it declared, exit 1.
  const std::string cut = box.write(
      "cut.bvh", "HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n}\nMOTION\nFrames: 120\n"
                 "Frame Time: 0.1\n1\n");
  const Run refused = box.cli("info \"" + cut + "\"");
  CHECK(refused.status == 1);
  CHECK(lines_in(refused.err) == 1);
  CHECK_THAT(refused.err, Catch::StartsWith("mostyle: " + cut + ":10: the file ends after 1 complete frame of the 120 "
                                            "that Frames: declares on line 8"));
  // Warnings go to stderr and the command still succeeds.
  const std::string more = box.write(
      "more.bvh", "HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n}\nMOTION\nFrames: 1\n"
                  "Frame Time: 0.1\n1\n2\n");
  const Run warned = box.cli("info \"" + more + "\"");
  CHECK(warned.status == 0);
  CHECK(warned.err == "mostyle: warning: " + more + ":8: Frames: says 1 but the file has 2 complete frames; loaded 2\n");
}

TEST_CASE("cli: MOSTYLE_MAX_MEMORY_MB bounds the memory a take's frames may need", "[cli][bvh]") {
  Sandbox box;
  std::string text =
      "HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 0\nCHANNELS 6 Xposition Yposition Zposition Zrotation "
      "Xrotation Yrotation\n}\nMOTION\nFrames: 30000\nFrame Time: 0.01\n";
  for (int f = 0; f < 30000; ++f) text += "0 0 0 0 0 0\n";  // 30000 x 6 x 8 bytes: 1.4 MB
  const std::string file = box.write("long.bvh", text);
  struct Environment {
    ~Environment() { ::unsetenv("MOSTYLE_MAX_MEMORY_MB"); }
  } restore;
  ::setenv("MOSTYLE_MAX_MEMORY_MB", "1", 1);
  Run r = box.cli("info \"" + file + "\"");
  CHECK(r.status == 1);
  CHECK(r.err == "mostyle: " + file + ":8: expected frames within the memory limit of 1 MB, found Frames: 30000 "
                                      "of 6 values each (1.4 MB)\n");
  // dtw's CSV series too: 140000 rows of one value, 1.1 MB of values.
  std::string series;
  for (int r = 0; r < 140000; ++r) series += "0\n";
  const std::string csv = box.write("long.csv", series);
  r = box.cli("dtw \"" + csv + "\" \"" + csv + "\" --json");
  CHECK(r.status == 1);
  CHECK(r.err == "mostyle: " + csv + ":131073: expected values within the memory limit of 1 MB, found 131073 rows "
                                     "of 1 value each (1.1 MB)\n");
  CHECK(r.out.empty());
  ::setenv("MOSTYLE_MAX_MEMORY_MB", "2", 1);
  CHECK(box.cli("info \"" + file + "\"").status == 0);
  for (const char* bad : {"0", "-1", "1.5", "lots", "99999999999999999999"}) {
    ::setenv("MOSTYLE_MAX_MEMORY_MB", bad, 1);
    r = box.cli("info \"" + file + "\"");
    CHECK(r.status == 1);
    CHECK(r.err == std::string("mostyle: MOSTYLE_MAX_MEMORY_MB: expected a whole number of megabytes from 1 up, "
                               "found '") + bad + "'\n");
  }
}

TEST_CASE("cli: bad usage exits 2", "[cli][bvh]") {
  Sandbox box;
  const std::string file = test::asset("motions/cmu142_walk_clumsy.bvh");
  CHECK(box.cli("").status == 2);
  CHECK(box.cli("frobnicate").status == 2);
  CHECK(box.cli("info").status == 2);
  CHECK(box.cli("info \"" + file + "\" --bogus").status == 2);
  CHECK(box.cli("fk \"" + file + "\"").status == 2);  // --out is required
  CHECK(box.cli("convert \"" + file + "\" \"" + box.path("o.bvh") + "\" --order ABC").status == 2);
  CHECK(box.cli("convert \"" + file + "\" \"" + box.path("o.bvh") + "\" --fps 0").status == 2);
  CHECK(box.cli("convert \"" + file + "\" \"" + box.path("o.bvh") + "\" --fps -30").status == 2);
  CHECK(box.cli("convert \"" + file + "\" \"" + box.path("o.bvh") + "\" --fps fast").status == 2);
  CHECK(box.cli("convert \"" + file + "\" \"" + box.path("o.bvh") + "\" --fps nan").status == 2);
  CHECK(box.cli("convert \"" + file + "\" \"" + box.path("o.bvh") + "\" --fps inf").status == 2);
  CHECK_FALSE(fs::exists(box.path("o.bvh")));
  CHECK(box.cli("info --help").status == 0);
}

TEST_CASE("cli: an output named in a format that is not written is refused, naming the formats; .fbx is written", "[cli][bvh]") {
  Sandbox box;
  const std::string file = test::asset("motions/cmu142_walk_clumsy.bvh");
  const std::string other = test::asset("motions/cmu142_walk_happy.bvh");
  for (const std::string out : {"x.mp4", "x.obj", "x", "x.bvh.txt", "x.fbx.txt"}) {
    const Run convert = box.cli("convert \"" + file + "\" \"" + box.path(out) + "\"");
    CHECK(convert.status == 2);
    CHECK(convert.err.find("BVH (.bvh), FBX (.fbx) and glTF 2.0 (.glb, .gltf)") != std::string::npos);
    CHECK(box.cli("blend \"" + file + "\" \"" + other + "\" --alpha 0.5 --out \"" + box.path(out) + "\"").status == 2);
    CHECK_FALSE(fs::exists(box.path(out)));
  }
  // Any case of a written format's extension is taken, and each is written in its format.
  CHECK(box.cli("convert \"" + file + "\" \"" + box.path("upper.BVH") + "\"").status == 0);
  CHECK(fs::exists(box.path("upper.BVH")));
  for (const std::string out : {"walk.fbx", "walk.FBX", "walk.glb"}) {
    INFO(out);
    CHECK(box.cli("convert \"" + file + "\" \"" + box.path(out) + "\"").status == 0);
    CHECK(read_motion_file(box.path(out)).skeleton.joint_count_without_end_sites() ==
          read_bvh_file(file).skeleton.joint_count_without_end_sites());
  }
  std::ifstream fbx(box.path("walk.fbx"), std::ios::binary);
  std::string magic(21, '\0');
  fbx.read(magic.data(), 21);
  CHECK(magic == std::string("Kaydara FBX Binary  \0", 21));
  CHECK(box.cli("blend \"" + file + "\" \"" + other + "\" --alpha 0.5 --out \"" + box.path("blend.fbx") + "\"").status == 0);
  CHECK(read_motion_file(box.path("blend.fbx")).frames() > 0);
}

TEST_CASE("cli fk writes frame,joint,x,y,z for every joint in file order", "[cli][bvh]") {
  Sandbox box;
  const std::string file = test::asset("motions/cmu142_walk_happy.bvh");
  const Run r = box.cli("fk \"" + file + "\" --out \"" + box.path("p.csv") + "\"");
  REQUIRE(r.status == 0);
  const Clip clip = read_bvh_file(file);
  const Eigen::MatrixXd p = joint_positions(clip);
  std::ifstream csv(box.path("p.csv"));
  std::string line;
  std::getline(csv, line);
  CHECK(line == "frame,joint,x,y,z");
  int rows = 0;
  double worst = 0;
  while (std::getline(csv, line)) {
    std::stringstream fields(line);
    std::string frame, joint, x, y, z;
    std::getline(fields, frame, ',');
    std::getline(fields, joint, ',');
    std::getline(fields, x, ',');
    std::getline(fields, y, ',');
    std::getline(fields, z, ',');
    const int f = std::stoi(frame);
    const int j = clip.skeleton.find(joint);
    REQUIRE(j >= 0);
    // Shortest round-trip text: the doubles come back exactly.
    worst = std::max({worst, std::abs(std::stod(x) - p(f, 3 * j)), std::abs(std::stod(y) - p(f, 3 * j + 1)),
                      std::abs(std::stod(z) - p(f, 3 * j + 2))});
    ++rows;
  }
  CHECK(rows == clip.frames() * 31);  // End Sites out
  CHECK(worst == 0.0);
}

TEST_CASE("cli convert: other order, other rate, same positions", "[cli][bvh]") {
  Sandbox box;
  const std::string file = test::asset("motions/cmu142_walk_marching.bvh");
  const Clip clip = read_bvh_file(file);
  const Eigen::MatrixXd p = joint_positions(clip);
  Run r = box.cli("convert \"" + file + "\" \"" + box.path("xyz.bvh") + "\" --order xyz");
  REQUIRE(r.status == 0);
  const Clip xyz = read_bvh_file(box.path("xyz.bvh"));
  CHECK(xyz.skeleton.joints[1].channels ==
        std::vector<Channel>{Channel::kXrotation, Channel::kYrotation, Channel::kZrotation});
  CHECK((joint_positions(xyz) - p).cwiseAbs().maxCoeff() < 1e-9 * 30);
  r = box.cli("convert \"" + file + "\" \"" + box.path("30.bvh") + "\" --fps 30 --order ZXY");
  REQUIRE(r.status == 0);
  const Clip slow = read_bvh_file(box.path("30.bvh"));
  CHECK(slow.frames() == (clip.frames() - 1) / 4 + 1);
  CHECK(slow.fps() == 30.0);
  const Eigen::MatrixXd ps = joint_positions(slow);
  for (int f = 0; f < slow.frames(); ++f) CHECK((ps.row(f) - p.row(4 * f)).cwiseAbs().maxCoeff() < 1e-9 * 30);
}

TEST_CASE("cli: a failed write exits 1 and leaves no file", "[cli][bvh]") {
  Sandbox box;
  const std::string file = test::asset("motions/cmu142_walk_clumsy.bvh");
  const std::string nowhere = box.path("no/such/dir/out.bvh");
  Run r = box.cli("convert \"" + file + "\" \"" + nowhere + "\"");
  CHECK(r.status == 1);
  CHECK(r.err.rfind("mostyle: " + nowhere + ": cannot write: ", 0) == 0);
  CHECK(lines_in(r.err) == 1);
  CHECK_FALSE(fs::exists(nowhere));
  // Over a folder: the temporary file is removed again.
  fs::create_directory(box.path("taken.csv"));
  r = box.cli("fk \"" + file + "\" --out \"" + box.path("taken.csv") + "\"");
  CHECK(r.status == 1);
  CHECK(lines_in(r.err) == 1);
  CHECK(box.count_files() == 0);
}

TEST_CASE("cli: glTF and FBX in, glTF out, FILE#ANIMATION and --take", "[cli][gltf]") {
  Sandbox box;
  const std::string bvh = test::asset("motions/cmu142_walk_clumsy.bvh");
  const std::string glb = box.path("clumsy.glb");
  Run r = box.cli("convert \"" + bvh + "\" \"" + glb + "\"");
  REQUIRE(r.status == 0);
  r = box.cli("info --json \"" + glb + "\"");
  CHECK(r.status == 0);
  CHECK(r.out.find("\"takes\": [") != std::string::npos);
  CHECK(r.out.find("\"name\": \"clumsy\"") != std::string::npos);
  CHECK(r.out.find("\"frames\": 1080") != std::string::npos);
  r = box.cli("info --take clumsy --fps 30 --json \"" + glb + "\"");
  CHECK(r.status == 0);
  CHECK(r.out.find("\"frames\": 270") != std::string::npos);
  r = box.cli("fk \"" + glb + "#clumsy\" --fps 30 --out \"" + box.path("p.csv") + "\"");
  CHECK(r.status == 0);
  CHECK(lines_in(test::slurp(box.path("p.csv"))) == 1 + 270 * 31);
  // A take the file does not have: one line naming file and animations, exit 1, nothing written.
  const int files = box.count_files();
  r = box.cli("convert \"" + glb + "#run\" \"" + box.path("run.bvh") + "\"");
  CHECK(r.status == 1);
  CHECK(lines_in(r.err) == 1);
  CHECK(r.err.find("clumsy.glb: has no animation 'run'; it has 'clumsy'") != std::string::npos);
  CHECK(box.count_files() == files);
  // A corrupt file: the same.
  const std::string bad = box.write("bad.glb", "glTF\x02\x00\x00\x00garbage");
  r = box.cli("info \"" + bad + "\"");
  CHECK(r.status == 1);
  CHECK(lines_in(r.err) == 1);
  CHECK(r.err.find("bad.glb: not a readable glTF file") != std::string::npos);
  const std::string bad_fbx = box.write("bad.fbx", "Kaydara FBX Binary  \0\x1a\x00garbage");
  r = box.cli("fk \"" + bad_fbx + "\" --out \"" + box.path("q.csv") + "\"");
  CHECK(r.status == 1);
  CHECK(lines_in(r.err) == 1);
  CHECK(r.err.find("bad.fbx: not a readable FBX file") != std::string::npos);
  CHECK_FALSE(fs::exists(box.path("q.csv")));
}

TEST_CASE("cli: a blend of two animations of one GLB exports a GLB that validates", "[cli][gltf][shared]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  Sandbox box;
  const std::string glb = test::shared_motion("formats/cmu142_walks_30fps.glb");
  const std::string out = box.path("blend.glb");
  Run r = box.cli("blend \"" + glb + "#cmu142_walk_happy\" \"" + glb + "#cmu142_walk_joy\" --alpha 0.5 --out \"" +
                  out + "\"");
  CHECK(r.status == 0);
  REQUIRE(fs::exists(out));
  MOSTYLE_CHECK_GLTF_VALID(out);
  // Without a take: the first, and a note naming the others.
  r = box.cli("info \"" + glb + "\"");
  CHECK(r.status == 0);
  CHECK(r.err.find("mostyle: note: ") == 0);
  CHECK(r.err.find("'cmu142_walk_happy', 'cmu142_walk_joy': pick one with FILE#NAME or --take NAME") !=
        std::string::npos);
  CHECK(r.out.find("    cmu142_walk_joy  (") != std::string::npos);
  // And it reads back: the reference's 31 joints.
  r = box.cli("info --json \"" + out + "\"");
  CHECK(r.status == 0);
  CHECK(r.out.find("\"name\": \"blend\"") != std::string::npos);
  // The same with mix, one take of the GLB and one FBX (FILE#ANIMATION names the FBX's stack).
  const std::string fbx = test::shared_motion("formats/cmu142_walk_happy_30fps.fbx");
  r = box.cli("mix \"" + glb + "#cmu142_walk_clumsy\" \"" + fbx + "#Scene\" --weights 0.5,0.5 --out \"" +
              box.path("mix.glb") + "\"");
  CHECK(r.status == 0);
  MOSTYLE_CHECK_GLTF_VALID(box.path("mix.glb"));
}
