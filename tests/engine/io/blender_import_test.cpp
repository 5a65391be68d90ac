// What Blender makes of the files mostyle writes and reads, checked with Blender itself
// (tests/blender/import_report.py: Blender's own importers, default settings). Skips, visibly,
// where Blender is not installed or cannot import glTF (Debian's Blender needs python3-numpy).

#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "engine/io/bvh/bvh_read.h"
#include "engine/io/motion_file.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/resample.h"
#include "engine/kinematics/units.h"
#include "tests/engine/io/temp_dir.h"
#include "tests/test_data.h"

namespace fs = std::filesystem;
using namespace mostyle;

namespace {

// Blender keeps key values and bone matrices in float32: its bones' heads lie within some 1e-5
// of the height of ours (the 14 animations' worst, at 30 fps: 1.5e-5).
constexpr double kBlenderMax = 5e-5;
constexpr double kBlenderMean = 1e-5;

using test::TempDir;

std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

bool has_blender() { return std::system("command -v blender >/dev/null 2>&1") == 0; }

// Blender's output (stdout and stderr) of tests/blender/SCRIPT run with `args`, in the background.
std::string run_blender(const TempDir& tmp, const std::string& script, const std::vector<std::string>& args) {
  std::string command = "blender -b --factory-startup --python " +
                        quoted((fs::path(MOSTYLE_BLENDER_SCRIPTS) / script).string()) + " --";
  for (const std::string& a : args) command += " " + quoted(a);
  const std::string log = tmp.path("blender.log");
  std::system((command + " >" + quoted(log) + " 2>&1").c_str());
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// import_report.py's line for `file`, or null with *why set when Blender could not import it for
// a reason of the machine's (its glTF importer without numpy).
nlohmann::json import_report(const TempDir& tmp, const std::string& file, double fps, std::string* why) {
  const std::string out = run_blender(tmp, "import_report.py", {file, std::to_string(fps)});
  const std::string tag = "import_report: ";
  const size_t at = out.rfind(tag);
  INFO(out.substr(out.size() > 2000 ? out.size() - 2000 : 0));
  REQUIRE(at != std::string::npos);
  nlohmann::json report = nlohmann::json::parse(out.substr(at + tag.size(), out.find('\n', at) - at - tag.size()));
  if (report.contains("error")) {
    if (out.find("No module named 'numpy'") != std::string::npos) {
      *why = "Blender's glTF importer needs numpy (python3-numpy)";
      return nullptr;
    }
    FAIL("Blender could not import " << file << ": " << report["error"]);
  }
  return report;
}

// Blender's heads of action `a` against our joints of the same names (every joint a bone is
// named after; End Sites too), frame by frame, in metres: the largest and mean distances as
// fractions of `height`. positions: frames x 3J, metres.
std::pair<double, double> head_error(const nlohmann::json& report, const nlohmann::json& action, const Clip& clip,
                                     const Eigen::MatrixXd& positions, double height) {
  std::vector<std::pair<int, int>> pairs;  // (bone, joint)
  const nlohmann::json& bones = report["bones"];
  for (size_t b = 0; b < bones.size(); ++b)
    for (size_t j = 0; j < clip.skeleton.joints.size(); ++j)
      if (clip.skeleton.joints[j].name == bones[b].get<std::string>())
        pairs.push_back({static_cast<int>(b), static_cast<int>(j)});
  REQUIRE(pairs.size() == bones.size());
  const nlohmann::json& heads = action["heads"];
  CHECK(static_cast<Eigen::Index>(heads.size()) == positions.rows());
  double worst = 0, sum = 0;
  long count = 0;
  for (Eigen::Index f = 0; f < std::min<Eigen::Index>(positions.rows(), heads.size()); ++f) {
    for (const auto& [b, j] : pairs) {
      const Eigen::Vector3d theirs(heads[f][3 * b].get<double>(), heads[f][3 * b + 1].get<double>(),
                                   heads[f][3 * b + 2].get<double>());
      const double d = (theirs - positions.block<1, 3>(f, 3 * j).transpose()).norm();
      worst = std::max(worst, d);
      sum += d;
      ++count;
    }
  }
  return {worst / height, count > 0 ? sum / count / height : 0.0};
}

}  // namespace

TEST_CASE("Blender: a take in CMU units written as glTF and FBX is one armature of every joint and End Site, "
          "in metres",
          "[blender][gltf][fbx]") {
  if (!has_blender()) {
    WARN("skipped: blender is not installed");
    return;
  }
  TempDir tmp;
  // Two seconds of the CMU walk at 30 fps: 31 joints and 7 End Sites, 29 CMU units tall.
  Clip clip = resample_clip(read_bvh_file(test::asset("motions/cmu142_walk_clumsy.bvh")), 30.0);
  clip.motion.conservativeResize(60, Eigen::NoChange);
  const double metres = metres_per_unit(clip);
  REQUIRE(metres == Approx(0.0254 / 0.45));
  const Eigen::MatrixXd ours = metres * joint_positions(clip);
  const std::vector<Eigen::Vector3d> first = pose_at(clip, 0).positions;
  double low = first[0].y(), high = low;
  for (const Eigen::Vector3d& p : first) {
    low = std::min(low, p.y());
    high = std::max(high, p.y());
  }
  const double height = metres * (high - low);  // about 1.6 m
  for (const char* ext : {".glb", ".fbx"}) {
    INFO(ext);
    const std::string file = tmp.path(std::string("walk") + ext);
    write_motion_file(clip, file);
    std::string why;
    const nlohmann::json report = import_report(tmp, file, 30.0, &why);
    if (report.is_null()) {
      WARN("skipped: " << why);
      return;
    }
    // One armature and nothing else: no End Site an Empty.
    CHECK(report["objects"] == nlohmann::json({{"ARMATURE", 1}}));
    CHECK(report["bones"].size() == clip.skeleton.joints.size());
    CHECK(report["height"].get<double>() == Approx(height).epsilon(1e-4));
    REQUIRE(report["actions"].size() == 1);
    const auto [worst, mean] = head_error(report, report["actions"][0], clip, ours, height);
    INFO("Blender's heads against ours: mean " << mean << ", max " << worst << " of the height");
    CHECK(worst <= kBlenderMax);
    CHECK(mean <= kBlenderMean);
  }
}

TEST_CASE("Blender: 14 animations that each move only some joints read as Blender plays them", "[blender][gltf]") {
  if (!has_blender()) {
    WARN("skipped: blender is not installed");
    return;
  }
  TempDir tmp;
  const std::string file = tmp.path("robot.glb");
  run_blender(tmp, "partial_animations.py", {file});
  REQUIRE(fs::exists(file));
  std::string why;
  const nlohmann::json report = import_report(tmp, file, 30.0, &why);
  if (report.is_null()) {
    WARN("skipped: " << why);
    return;
  }
  REQUIRE(report["actions"].size() == 14);
  const std::vector<TakeInfo> takes = read_motion_takes(file);
  REQUIRE(takes.size() == 14);
  int partial = 0;
  for (const TakeInfo& take : takes) partial += take.moves < 18 ? 1 : 0;
  CHECK(partial == 12);
  MotionReadOptions o;
  o.fps = 30.0;
  for (const nlohmann::json& action : report["actions"]) {
    const std::string name = action["name"];
    INFO(name);
    const Clip clip = read_motion_file(file + "#" + name, nullptr, o);
    const double height = guess_units(clip).height;
    const auto [worst, mean] = head_error(report, action, clip, joint_positions(clip), height);
    INFO("Blender's heads against ours: mean " << mean << ", max " << worst << " of the height");
    CHECK(worst <= kBlenderMax);
    CHECK(mean <= kBlenderMean);
  }
}
