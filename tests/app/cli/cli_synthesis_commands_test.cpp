// mostyle-cli mix and transfer, run as a user runs them: mix of two is blend, weights
// are checked before anything is read, transfer at strength 0 is the content take, bad input
// exits 1 with one line and leaves no file.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "engine/synthesize/mix_palette.h"
#include "tests/app/cli/cli_sandbox.h"
#include "tests/test_data.h"

using namespace mostyle;

namespace {

class Sandbox : public test::CliSandbox {
 public:
  Sandbox() : test::CliSandbox("mostyle_cli_palette_test") {}
};

// The x, y, z columns of a positions CSV (frame,joint,x,y,z; names without commas).
std::vector<double> positions(const std::string& csv) {
  std::vector<double> values;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    size_t at = line.find(',');
    at = line.find(',', at + 1);
    std::istringstream fields(line.substr(at + 1));
    std::string v;
    while (std::getline(fields, v, ',')) values.push_back(std::stod(v));
  }
  return values;
}

double max_difference(const std::vector<double>& a, const std::vector<double>& b) {
  REQUIRE(a.size() == b.size());
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

// positions() as each joint's height and horizontal distance from its frame's root (its first
// joint): the poses where they stand, whatever path the root takes and wherever it faces.
// joints: per frame.
std::vector<double> on_root(const std::vector<double>& values, size_t joints, const std::vector<bool>& kept = {}) {
  std::vector<double> out;
  for (size_t frame = 0; frame + 3 * joints <= values.size(); frame += 3 * joints)
    for (size_t j = 0; j < joints; ++j) {
      if (!kept.empty() && !kept[j]) continue;
      const size_t at = frame + 3 * j;
      out.push_back(std::hypot(values[at] - values[frame], values[at + 2] - values[frame + 2]));
      out.push_back(values[at + 1]);
    }
  return out;
}

std::string quoted(const std::string& path) { return "\"" + path + "\""; }

const std::string kHappy = quoted(test::asset("motions/cmu142_walk_happy.bvh"));
const std::string kMarching = quoted(test::asset("motions/cmu142_walk_marching.bvh"));
const std::string kJoy = quoted(test::asset("motions/cmu142_walk_joy.bvh"));
const std::string kClumsy = quoted(test::asset("motions/cmu142_walk_clumsy.bvh"));

}  // namespace

TEST_CASE("cli mix A B --weights 0.5,0.5 is blend A B --alpha 0.5", "[cli][palette]") {
  Sandbox box;
  const auto blend = box.cli("blend " + kHappy + " " + kMarching + " --alpha 0.5 --positions-out " +
                             quoted(box.path("blend.csv")) + " --report " + quoted(box.path("blend.json")));
  REQUIRE(blend.status == 0);
  const auto mix = box.cli("mix " + kHappy + " " + kMarching + " --weights 0.5,0.5 --positions-out " +
                           quoted(box.path("mix.csv")) + " --report " + quoted(box.path("mix.json")));
  INFO(mix.err);
  REQUIRE(mix.status == 0);
  const auto report = nlohmann::json::parse(test::slurp(box.path("blend.json")));
  const double height = report["skeleton_height"];
  const auto mix_report = nlohmann::json::parse(test::slurp(box.path("mix.json")));
  CHECK(mix_report["frames"] == report["frames"]);
  CHECK(max_difference(positions(test::slurp(box.path("mix.csv"))), positions(test::slurp(box.path("blend.csv")))) <
        0.005 * height);
  CHECK(mix_report["takes"].size() == 2);
  CHECK(mix_report["component_joints"].size() == 10);
}

TEST_CASE("cli mix: bad weights exit 1 with one line and write nothing", "[cli][palette]") {
  Sandbox box;
  const std::string out = " --out " + quoted(box.path("out.bvh"));
  for (const char* weights : {"0.5,0.6,0", "2,-0.5,-0.5", "0.5,0.5", "a,b,c"}) {
    const auto r = box.cli("mix " + kHappy + " " + kMarching + " " + kJoy + " --weights " + weights + out);
    INFO(weights << ": " << r.err);
    CHECK(r.status != 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') <= 2);
    CHECK(box.count_files() == 0);
  }
  const auto one = box.cli("mix " + kHappy + out);
  CHECK(one.status == 1);
  CHECK(one.err.find("from 2 to 16") != std::string::npos);
  const auto part = box.cli("mix " + kHappy + " " + kMarching + " --part-weights legs:0.5" + out);
  CHECK(part.status == 1);
  CHECK(part.err.find("--part-weights") != std::string::npos);
  CHECK(box.count_files() == 0);
}

TEST_CASE("cli blend: an alpha mix would refuse as a weight exits 1 with one line and writes nothing",
          "[cli][palette]") {
  // alpha is B's weight and 1 - alpha A's: mix takes each from -0.5 to 1.5, so blend does too.
  Sandbox box;
  const std::string out = " --out " + quoted(box.path("out.bvh"));
  for (const std::string& alpha : {std::string(" --alpha 5"), std::string(" --alpha -0.6"), std::string(" --alpha 1.51"),
                                   std::string(" --part-alpha legs:2"), std::string(" --alpha-at 0:0,1:3"),
                                   std::string(" --component-alpha 0,0,0,0,0,0,0,0,0,9")}) {
    const auto r = box.cli("blend " + kHappy + " " + kMarching + alpha + out);
    INFO(alpha << ": " << r.err);
    CHECK(r.status == 1);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err.find("from -0.5 to 1.5") != std::string::npos);
    CHECK(box.count_files() == 0);
  }
  // The ends of the range are blends.
  const auto edge = box.cli("blend " + kHappy + " " + kMarching + " --alpha 1.5 --positions-out " +
                            quoted(box.path("edge.csv")));
  INFO(edge.err);
  CHECK(edge.status == 0);
}

TEST_CASE("cli mix of four takes with per-part weights, and transfer, write BVH files", "[cli][palette]") {
  Sandbox box;
  const auto mix = box.cli("mix " + kHappy + " " + kMarching + " " + kJoy + " " + kClumsy +
                           " --weights 0.4,0.2,0.2,0.2 --part-weights legs:0,1,0,0 --out " + quoted(box.path("mix.bvh")) +
                           " --report " + quoted(box.path("mix.json")));
  INFO(mix.err);
  REQUIRE(mix.status == 0);
  const auto report = nlohmann::json::parse(test::slurp(box.path("mix.json")));
  CHECK(report["takes"].size() == 4);
  CHECK(report["part_weights"]["legs"].size() == 4);
  CHECK(report["export_fit"]["max"].get<double>() < 0.05 * report["skeleton_height"].get<double>());
  CHECK(report["channels"] == "rotations");

  const auto transfer = box.cli("transfer " + kClumsy + " --neutral " + kHappy + " --style " + kMarching +
                                " --strength 0 --no-foot-lock --positions-out " + quoted(box.path("t.csv")) +
                                " --report " + quoted(box.path("t.json")));
  INFO(transfer.err);
  REQUIRE(transfer.status == 0);
  const auto t = nlohmann::json::parse(test::slurp(box.path("t.json")));
  CHECK(t["weights"] == std::vector<double>{1.0, 0.0, 0.0});
  CHECK(t["fps"] == 120.0);  // the content's own rate (CMU: 120 fps)...
  const auto at30 = box.cli("transfer " + kClumsy + " --neutral " + kHappy + " --style " + kMarching +
                            " --fps 30 --report " + quoted(box.path("t30.json")));
  REQUIRE(at30.status == 0);
  CHECK(nlohmann::json::parse(test::slurp(box.path("t30.json")))["fps"] == 30.0);  // ... unless --fps says
  const auto bad = box.cli("transfer " + kClumsy + " --neutral " + kHappy + " --style " + kMarching +
                           " --strength 3 --out " + quoted(box.path("bad.bvh")));
  CHECK(bad.status == 1);
  CHECK(!std::filesystem::exists(box.path("bad.bvh")));
}

TEST_CASE("cli transfer without --neutral: the content is its own neutral", "[cli][palette]") {
  Sandbox box;
  auto run = [&](const std::string& args, const std::string& name) {
    const auto r = box.cli(args + " --no-foot-lock --positions-out " + quoted(box.path(name + ".csv")) + " --report " +
                           quoted(box.path(name + ".json")));
    INFO(args << ": " << r.err);
    REQUIRE(r.status == 0);
    return nlohmann::json::parse(test::slurp(box.path(name + ".json")));
  };
  // Strength 0: the content, frame for frame, as the transfer with a neutral take gives it (its
  // frames read on another common timeline: within a thousandth of the height).
  const auto zero = run("transfer " + kClumsy + " --style " + kMarching + " --strength 0", "zero");
  CHECK(zero["neutral"].is_null());
  CHECK(zero["weights"] == std::vector<double>{1.0, 0.0});
  REQUIRE(zero["takes"].size() == 2);
  CHECK(zero["takes"][1]["file"] == test::asset("motions/cmu142_walk_marching.bvh"));
  const auto with_neutral = run("transfer " + kClumsy + " --neutral " + kHappy + " --style " + kMarching +
                                " --strength 0", "with_neutral");
  const double height = zero["skeleton_height"];
  CHECK(zero["frames"] == with_neutral["frames"]);
  CHECK(max_difference(positions(test::slurp(box.path("zero.csv"))),
                       positions(test::slurp(box.path("with_neutral.csv")))) < 1e-3 * height);
  // Strength 1: the mix of content and style with weights 0 and 1 on the content's timeline (the
  // style on the content's timing), the content the reference; strength 0.4: the mix (0.6, 0.4).
  // The same poses where they stand; the path the content's, within the leash, facing as it does
  // (the mix walks the style's).
  run("transfer " + kClumsy + " --style " + kMarching + " --strength 0 --fps 60", "content60");
  for (const std::string s : {"1", "0.4"}) {
    const double strength = std::stod(s);
    const auto t = run("transfer " + kClumsy + " --style " + kMarching + " --strength " + s + " --fps 60", "t" + s);
    const auto m = run("mix " + kClumsy + " " + kMarching + " --weights " + std::to_string(1.0 - strength) + "," + s +
                           " --fps 60 --timing reference",
                       "m" + s);
    CHECK(t["weights"][0].get<double>() == Approx(1.0 - strength));
    CHECK(t["frames"] == m["frames"]);
    const size_t joints = t["joints"].size();
    const std::vector<double> transferred = positions(test::slurp(box.path("t" + s + ".csv")));
    const std::vector<double> mixed = positions(test::slurp(box.path("m" + s + ".csv")));
    // Within 2% of the height: the speed limit allows a joint what the root's own step leaves,
    // so where the root goes at another pace it spreads a fast step a little differently. The
    // legs below the hips' joints apart: their strides are fitted to the content's pace.
    std::vector<bool> above_knees;
    for (const auto& name : t["joints"]) {
      const std::string n = name.get<std::string>();
      above_knees.push_back(n.find("Leg") == std::string::npos || n.find("UpLeg") != std::string::npos);
      above_knees.back() = above_knees.back() && n.find("Foot") == std::string::npos && n.find("Toe") == std::string::npos;
    }
    REQUIRE(std::count(above_knees.begin(), above_knees.end(), false) == 6);
    CHECK(max_difference(on_root(transferred, joints, above_knees), on_root(mixed, joints, above_knees)) <
          0.02 * height);
    // The hips of the last frame: the mix's far off the content's path, the transfer's within the
    // leash of it (the content at strength 0 walks it; the same frames shown).
    const std::vector<double> content = positions(test::slurp(box.path("content60.csv")));
    REQUIRE(content.size() == transferred.size());
    const size_t last = transferred.size() - 3 * joints;
    const auto ground_gap = [&](const std::vector<double>& v) {
      return std::hypot(v[last] - content[last], v[last + 2] - content[last + 2]) / height;
    };
    INFO("strength " << s << ": the mix's hips " << ground_gap(mixed) << ", the transfer's " << ground_gap(transferred)
                     << " heights from the content's");
    CHECK(ground_gap(mixed) > kOwnNeutralPathLeash);
    CHECK(ground_gap(transferred) < kOwnNeutralPathLeash);
  }
  // With a neutral take, on the content's timing: the content's path too, frame by frame, through
  // its turns, the drift of the style's shorter or longer steps taken away (its travel kept).
  run("transfer " + kClumsy + " --neutral " + kHappy + " --style " + kMarching + " --strength 0 --fps 60", "n0");
  const auto neutral_path = run("transfer " + kClumsy + " --neutral " + kHappy + " --style " + kMarching + " --fps 60", "n1");
  {
    const std::vector<double> styled = positions(test::slurp(box.path("n1.csv")));
    const std::vector<double> content = positions(test::slurp(box.path("n0.csv")));
    REQUIRE(styled.size() == content.size());
    const size_t row = 3 * neutral_path["joints"].size();
    double worst = 0.0, sum = 0.0;
    for (size_t at = 0; at < styled.size(); at += row) {  // the hips, the first joint
      const double gap = std::hypot(styled[at] - content[at], styled[at + 2] - content[at + 2]) / height;
      worst = std::max(worst, gap);
      sum += gap;
    }
    const double mean = sum / static_cast<double>(styled.size() / row);
    INFO("the hips' gap from the content's: worst " << worst << ", mean " << mean << " body heights");
    CHECK(worst < kOwnNeutralPathLeash);
    CHECK(mean < 0.05);
  }
  // Keys: from none of the style to all of it; two styles each with its own strength.
  const auto keyed = run("transfer " + kClumsy + " --style " + kMarching + " --strength-at 0:0,2:1", "keyed");
  REQUIRE(keyed["keys"].size() == 2);
  CHECK(keyed["keys"][0]["weights"] == std::vector<double>{1.0, 0.0});
  CHECK(keyed["keys"][1]["weights"] == std::vector<double>{0.0, 1.0});
  // Before the first key the output is the content: its first frame as at strength 0.
  const std::vector<double> first_keyed = positions(test::slurp(box.path("keyed.csv")));
  const std::vector<double> first_zero = positions(test::slurp(box.path("zero.csv")));
  const size_t row = 3 * keyed["joints"].size();
  CHECK(max_difference(std::vector<double>(first_keyed.begin(), first_keyed.begin() + row),
                       std::vector<double>(first_zero.begin(), first_zero.begin() + row)) < 1e-6 * height);
  const auto two = run("transfer " + kClumsy + " --style " + kMarching + " --style " + kJoy +
                           " --strength-at \"0:0,0;1:1,0.5\"",
                       "two");
  CHECK(two["keys"][1]["weights"] == std::vector<double>{-0.5, 1.0, 0.5});
  // Without --report: the summary says the content is its own neutral.
  const auto summary = box.cli("transfer " + kClumsy + " --style " + kMarching + " --positions-out " +
                               quoted(box.path("s.csv")));
  REQUIRE(summary.status == 0);
  CHECK(summary.out.find("transfer onto cmu142_walk_clumsy.bvh (its own neutral) to cmu142_walk_marching.bvh") !=
        std::string::npos);
}

TEST_CASE("cli transfer keeps the content's length and timing unless --timing mix", "[cli][palette]") {
  Sandbox box;
  const auto info = box.cli("info " + kClumsy + " --json");
  REQUIRE(info.status == 0);
  const long content_frames = nlohmann::json::parse(info.out)["frames"];
  auto frames = [&](const std::string& timing, const std::string& name) {
    const auto r = box.cli("transfer " + kClumsy + " --neutral " + kHappy + " --style " + kMarching + timing +
                           " --report " + quoted(box.path(name + ".json")));
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto report = nlohmann::json::parse(test::slurp(box.path(name + ".json")));
    CHECK(report["timing"] == (timing.empty() ? "content" : timing.substr(timing.rfind(' ') + 1)));
    return report["frames"].get<long>();
  };
  CHECK(frames("", "default") == content_frames);  // at the content's own rate
  CHECK(frames(" --timing content", "content") == content_frames);
  CHECK(frames(" --timing mix", "mix") != content_frames);  // the style's timing change: another length
}

TEST_CASE("cli mix: typed weights within 0.001 of a sum of 1 and fractions are taken and normalized",
          "[cli][palette]") {
  Sandbox box;
  // Three thirds typed as fractions: the report gives the weights typed and the ones used.
  const auto thirds = box.cli("mix " + kHappy + " " + kMarching + " " + kJoy +
                              " --weights 1/3,1/3,1/3 --part-weights legs:1/2,1/4,1/4 --report " +
                              quoted(box.path("thirds.json")));
  INFO(thirds.err);
  REQUIRE(thirds.status == 0);
  CHECK(thirds.out.empty());  // the report went to its file
  const auto r = nlohmann::json::parse(test::slurp(box.path("thirds.json")));
  CHECK(r["weights"][0].get<double>() == Approx(1.0 / 3.0).epsilon(1e-12));
  CHECK(r["part_weights"]["legs"][1].get<double>() == Approx(0.25));
  // Six-digit decimals whose sum is 1.000002: divided by their sum, and a summary on stdout
  // instead of the JSON.
  const auto rounded = box.cli("mix " + kHappy + " " + kMarching + " " + kJoy + " --weights 0.333334,0.333334,0.333334");
  INFO(rounded.err);
  REQUIRE(rounded.status == 0);
  CHECK(rounded.out.find('{') == std::string::npos);
  CHECK(rounded.out.find("mix of 3 takes") != std::string::npos);
  CHECK(rounded.out.find("frames at 30 fps") != std::string::npos);
  CHECK(rounded.out.find("nothing written") != std::string::npos);
  CHECK(std::count(rounded.out.begin(), rounded.out.end(), '\n') <= 6);
  // Further off than 0.001, a fraction over zero, or no number: refused before anything is read.
  for (const char* weights : {"0.33,0.33,0.33", "1/0,0,0", "1/3,1/3,x"}) {
    const auto bad = box.cli("mix " + kHappy + " " + kMarching + " " + kJoy + " --weights " + weights);
    INFO(weights << ": " << bad.err);
    CHECK(bad.status == 1);
    CHECK(std::count(bad.err.begin(), bad.err.end(), '\n') == 1);
  }
}

TEST_CASE("cli blend without --report prints a short summary, not the JSON", "[cli][palette]") {
  Sandbox box;
  const auto blend = box.cli("blend " + kHappy + " " + kMarching + " --alpha 0.3 --out " + quoted(box.path("b.bvh")));
  INFO(blend.err);
  REQUIRE(blend.status == 0);
  CHECK(blend.out.find("blend of cmu142_walk_happy.bvh and cmu142_walk_marching.bvh at alpha 0.30") !=
        std::string::npos);
  CHECK(blend.out.find("wrote " + box.path("b.bvh")) != std::string::npos);
  CHECK(blend.out.find("fastest joint ") != std::string::npos);  // the measures the report has
  CHECK(blend.out.find('{') == std::string::npos);
  CHECK(blend.out.size() < 1000);
}

TEST_CASE("cli report: the result's measures beside the takes', as the summary and the editor show them",
          "[cli][palette]") {
  Sandbox box;
  const auto r = box.cli("mix " + kHappy + " " + kMarching + " " + kJoy + " --report " + quoted(box.path("m.json")));
  INFO(r.err);
  REQUIRE(r.status == 0);
  const auto j = nlohmann::json::parse(test::slurp(box.path("m.json")));
  double fastest = 0.0;
  REQUIRE(j["takes"].size() == 3);
  for (const auto& t : j["takes"]) {
    CHECK(t["fastest_joint"].get<double>() > 0.0);
    CHECK(t["foot_sliding"].get<double>() >= 0.0);
    fastest = std::max(fastest, t["fastest_joint"].get<double>());
  }
  const auto& f = j["fastest_joint"];
  CHECK(f["inputs"].get<double>() == fastest);  // equal weights: every take is mixed
  CHECK(f["ratio"].get<double>() == Approx(f["result"].get<double>() / fastest));
  CHECK(f["ratio"].get<double>() <= 1.25);  // no pops
  const auto& feet = j["foot_sliding"];
  CHECK(feet["ratio"].get<double>() == Approx(feet["cleaned"].get<double>() / feet["inputs"].get<double>()));
  CHECK(j["limb_length_max_error"].get<double>() >= 0.0);
}

TEST_CASE("cli summaries with keys in time say the keys, not the constant weight they replace", "[cli][palette]") {
  Sandbox box;
  auto summary = [&](const std::string& args) {
    const auto r = box.cli(args + " --positions-out " + quoted(box.path("out.csv")));
    INFO(args << ": " << r.err);
    REQUIRE(r.status == 0);
    return r.out;
  };
  const std::string transfer = summary("transfer " + kClumsy + " --style " + kMarching + " --strength-at 0:0,2:1");
  CHECK(transfer.find("strength keyed 0.00 at 0.00 s, 1.00 at 2.00 s") != std::string::npos);
  CHECK(transfer.find("strength 1.00") == std::string::npos);
  const std::string blend = summary("blend " + kHappy + " " + kMarching + " --alpha-at 0:0,3:1");
  CHECK(blend.find("alpha keyed 0.00 at 0.00 s, 1.00 at 3.00 s") != std::string::npos);
  CHECK(blend.find("at alpha 0.50") == std::string::npos);
  const std::string mix = summary("mix " + kHappy + " " + kMarching + " " + kJoy + " --weights-at \"0:1,0,0;2:0,1/2,1/2\"");
  CHECK(mix.find("weights keyed 1.000 0.000 0.000 at 0.00 s, 0.000 0.500 0.500 at 2.00 s") != std::string::npos);
}

TEST_CASE("cli: one length for one motion, in hundredths of a second", "[cli][palette]") {
  Sandbox box;
  // info and a transfer at strength 0 (the content itself, on its own timeline) say one length.
  const auto info = box.cli("info " + kClumsy);
  REQUIRE(info.status == 0);
  const auto json = box.cli("info " + kClumsy + " --json");
  const auto clip = nlohmann::json::parse(json.out);
  char words[32];
  std::snprintf(words, sizeof words, "%.2f s", clip["duration_s"].get<double>());  // first frame to last
  CHECK(info.out.find(std::string("duration: ") + words + "\n") != std::string::npos);
  const auto transfer = box.cli("transfer " + kClumsy + " --style " + kMarching + " --strength 0 --positions-out " +
                                quoted(box.path("t.csv")));
  INFO(transfer.err);
  REQUIRE(transfer.status == 0);
  CHECK(transfer.out.find(std::string("(") + words + ")") != std::string::npos);
}

TEST_CASE("cli: whole takes by cycles, and style keyed in time", "[cli][palette]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  Sandbox box;
  const std::string normal = quoted(test::shared_motion("bandai_walk_normal.bvh"));  // 6.5 s at 30 fps
  const std::string tired = quoted(test::shared_motion("bandai_walk_tired.bvh"));
  // A 9 s content at 120 fps styled by a shorter pair keeps all its frames at its own rate, and
  // at strength 0 is itself.
  const auto whole = box.cli("transfer " + kClumsy + " --neutral " + normal + " --style " + tired +
                             " --strength 0 --report " + quoted(box.path("w.json")));
  INFO(whole.err);
  REQUIRE(whole.status == 0);
  const auto w = nlohmann::json::parse(test::slurp(box.path("w.json")));
  CHECK(w["fps"] == 120.0);
  const auto info = box.cli("info " + kClumsy + " --json");
  const auto clip = nlohmann::json::parse(info.out);
  CHECK(w["frames"] == clip["frames"]);
  CHECK(w["takes"][1]["time_base"] == "cycles");
  CHECK(w["takes"][1]["alignment"]["time_base"] == "cycles");
  // Which of the neutral's own cycles each output frame shows: several, reused.
  const std::vector<int> cycles = w["takes"][1]["source_cycles"];
  CHECK(*std::max_element(cycles.begin(), cycles.end()) >= 2);
  // Keyed: from none of the style to all of it over four seconds.
  const auto keyed = box.cli("transfer " + kClumsy + " --neutral " + normal + " --style " + tired +
                             " --strength-at 0:0,4:1 --report " + quoted(box.path("k.json")));
  INFO(keyed.err);
  REQUIRE(keyed.status == 0);
  const auto k = nlohmann::json::parse(test::slurp(box.path("k.json")));
  REQUIRE(k["keys"].size() == 2);
  CHECK(k["keys"][1]["weights"] == std::vector<double>{1.0, -1.0, 1.0});
  const auto blend = box.cli("blend " + normal + " " + tired + " --alpha-at 0:0,3:1 --report " +
                             quoted(box.path("b.json")));
  REQUIRE(blend.status == 0);
  CHECK(nlohmann::json::parse(test::slurp(box.path("b.json")))["keys"][1]["weights"] == std::vector<double>{0.0, 1.0});
  const auto mix = box.cli("mix " + kHappy + " " + kMarching + " " + kJoy + " --weights-at \"0:1,0,0;2:0,1/2,1/2\" --report " +
                           quoted(box.path("m.json")));
  INFO(mix.err);
  REQUIRE(mix.status == 0);
  // Bad keys: one line, exit 1, nothing written.
  const std::string out = " --out " + quoted(box.path("bad.bvh"));
  for (const std::string& bad : {"blend " + kHappy + " " + kJoy + " --alpha-at 5:0,1:1",
                                 "blend " + kHappy + " " + kJoy + " --alpha-at 0:0,5",
                                 "mix " + kHappy + " " + kJoy + " " + kClumsy + " --weights-at 0:1,0",
                                 "mix " + kHappy + " " + kJoy + " --weights-at 0:1,0 --part-weights legs:0,1",
                                 "transfer " + kClumsy + " --neutral " + normal + " --style " + tired +
                                     " --strength-at 0:0,4:7"}) {
    const auto r = box.cli(bad + out);
    INFO(bad << ": " << r.err);
    CHECK(r.status == 1);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(!std::filesystem::exists(box.path("bad.bvh")));
  }
}

TEST_CASE("cli blend: every wild walk and run blends with a Bandai walk, whatever its rig", "[cli][shared]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  Sandbox box;
  const std::string bandai = quoted(test::shared_motion("bandai_walk_normal.bvh"));
  for (const std::string take :
       {"gltf_cesiumman_walk.glb", "gltf_godot_robot_walk_run.glb#walk", "gltf_godot_robot_walk_run.glb#run",
        "gltf_mannequiny_run.glb#run_root.001", "gltf_godot_mixamo_walk_run.glb#walking",
        "gltf_godot_mixamo_walk_run.glb#running", "fbx_mixamo_walking.fbx", "xia_sexy_01.bvh",
        "xia_neutral_16.bvh", "aalto_t_walk_regular.bvh"}) {
    INFO(take);
    const size_t hash = take.find('#');
    const std::string path = test::shared_motion("wild/" + take.substr(0, hash)) +
                             (hash == std::string::npos ? "" : take.substr(hash));
    const auto r = box.cli("blend " + quoted(path) + " " + bandai +
                           " --alpha 0.5 --out " + quoted(box.path("x.bvh")) + " --report " +
                           quoted(box.path("x.json")));
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto report = nlohmann::json::parse(test::slurp(box.path("x.json")));
    CHECK(report["takes"][0]["major_joints"]["joints"].size() == 20);
    CHECK(report["takes"][1]["major_joints"]["how"] == "18 by name; missing: left_hand, right_hand");
  }
  // The summary says how a take's joints were found where it was not all by name.
  const auto r = box.cli("blend " + quoted(test::shared_motion("wild/gltf_cesiumman_walk.glb")) + " " + bandai +
                         " --alpha 0.5");
  REQUIRE(r.status == 0);
  CHECK(r.out.find("  major joints of gltf_cesiumman_walk.glb: 18 by structure (structure: hips") != std::string::npos);
  CHECK(r.out.find("major joints of bandai_walk_normal.bvh") == std::string::npos);
}

TEST_CASE("cli transfer onto a standing loop: the loop travels as its content does, so planted feet do not creep",
          "[cli][shared]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  if (test::shared_motion("actions/bandai_respond_normal.bvh").empty()) return;
  Sandbox box;
  // A reply gesture that reads as one loop (its last pose its first), styled by a musical
  // good-bye whose hips wander: the output is one loop too, its seam closed.
  const auto r = box.cli("transfer " + quoted(test::shared_motion("actions/bandai_respond_normal.bvh")) + " --style " +
                         quoted(test::shared_motion("actions/bandai_bye_musical.bvh")) + " --positions-out " +
                         quoted(box.path("t.csv")) + " --report " + quoted(box.path("t.json")));
  INFO(r.err);
  REQUIRE(r.status == 0);
  const auto report = nlohmann::json::parse(test::slurp(box.path("t.json")));
  const double height = report["foot_sliding"]["body_height"];
  // The hips' first and last frames, where the next repeat takes over: the content stands.
  std::istringstream in(test::slurp(box.path("t.csv")));
  std::string line;
  std::getline(in, line);
  std::vector<Eigen::Vector2d> hips;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::istringstream fields(line);
    for (std::string v; std::getline(fields, v, ',');) f.push_back(v);
    if (f.size() == 5 && f[1] == "Hips") hips.emplace_back(std::stod(f[2]), std::stod(f[4]));
  }
  REQUIRE(hips.size() > 10);
  // It drifted 1.6% of the height over the loop, and the planted feet crept as far (2.85 times
  // the content's planted speed).
  CHECK((hips.back() - hips.front()).norm() < 0.01 * height);
  CHECK(report["foot_sliding"]["ratio"].get<double>() < 2.0);
}

namespace {

// One joint's positions about the hips, frame by frame, from a positions CSV (frame,joint,x,y,z).
std::vector<Eigen::Vector3d> about_hips(const std::string& csv, const std::string& joint) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<Eigen::Vector3d> hips, at;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::istringstream fields(line);
    for (std::string v; std::getline(fields, v, ',');) f.push_back(v);
    if (f.size() != 5) continue;
    const Eigen::Vector3d p(std::stod(f[2]), std::stod(f[3]), std::stod(f[4]));
    if (f[1] == "Hips") hips.push_back(p);
    if (f[1] == joint) at.push_back(p);
  }
  for (size_t k = 0; k < std::min(hips.size(), at.size()); ++k) at[k] -= hips[k];
  return at;
}

// The RMS distance of positions from their mean: how much a joint moves.
double movement(const std::vector<Eigen::Vector3d>& p) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& x : p) mean += x;
  mean /= double(std::max<size_t>(1, p.size()));
  double sum = 0.0;
  for (const auto& x : p) sum += (x - mean).squaredNorm();
  return std::sqrt(sum / double(std::max<size_t>(1, p.size())));
}

}  // namespace

TEST_CASE("cli transfer across actions: a joint the content holds still is not set moving by another action's strokes",
          "[cli][shared]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  if (test::shared_motion("actions/bandai2_raise-up-right-hand_normal.bvh").empty()) return;
  Sandbox box;
  const auto act = [](const char* name) { return quoted(test::shared_motion(std::string("actions/") + name)); };
  // A raised right hand styled by a left-hand wave's normal -> youthful: the youthful wave's arm
  // moves unlike the normal's, stroke for stroke, but the raise holds its left arm still (it
  // moved 6 times as much, 0.073 of the height against the content's 0.012, before).
  const std::string base = "transfer " + act("bandai2_raise-up-right-hand_normal.bvh") + " --neutral " +
                           act("bandai2_wave-left-hand_normal.bvh") + " --style " + act("bandai2_wave-left-hand_youthful.bvh");
  for (const char* strength : {"0", "1"}) {
    const auto r = box.cli(base + " --strength " + strength + " --positions-out " + quoted(box.path(std::string("s") + strength + ".csv")) +
                           " --report " + quoted(box.path("s.json")));
    INFO(r.err);
    REQUIRE(r.status == 0);
  }
  const double height = nlohmann::json::parse(test::slurp(box.path("s.json")))["foot_sliding"]["body_height"];
  const std::string content = test::slurp(box.path("s0.csv")), out = test::slurp(box.path("s1.csv"));
  // The left arm as still as the content's, within 1% of the height; the raised right hand
  // moving as much as the content's, within a tenth.
  CHECK(movement(about_hips(out, "Hand_L")) <= movement(about_hips(content, "Hand_L")) + 0.01 * height);
  CHECK(movement(about_hips(out, "Hand_R")) == Approx(movement(about_hips(content, "Hand_R"))).epsilon(0.1));
}

TEST_CASE("cli transfer across actions keeps planted feet within 1.25x the content's", "[cli][shared]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  if (test::shared_motion("actions/bandai_kick_normal.bvh").empty()) return;
  Sandbox box;
  const auto act = [](const char* name) { return quoted(test::shared_motion(std::string("actions/") + name)); };
  // A loop of a reply styled by a good-bye whose style rest ends after the reply's last frame:
  // the loop lands where the reply's clock ends, so that rest is not squeezed into its last frame
  // and the seam is not spread over feet that never swing (1.51x before). And a kick whose left
  // foot skims the floor through its strokes, given a sad walk's posture: the foot is not held
  // where it drags, so the lock pins its stands rather than one stance over the whole take,
  // which it gave up on (1.37x before).
  for (const std::string args :
       {"transfer " + act("bandai_respond_normal.bvh") + " --neutral " + act("bandai_bye_normal.bvh") + " --style " +
            act("bandai_bye_musical.bvh"),
        "transfer " + act("bandai_kick_normal.bvh") + " --style " + quoted(test::shared_motion("bandai_walk_sad.bvh"))}) {
    INFO(args);
    const auto r = box.cli(args + " --report " + quoted(box.path("t.json")));
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto report = nlohmann::json::parse(test::slurp(box.path("t.json")));
    CHECK(report["foot_sliding"]["ratio"].get<double>() <= 1.25);
    CHECK(report["fastest_joint"]["ratio"].get<double>() <= 1.25);
  }
}
