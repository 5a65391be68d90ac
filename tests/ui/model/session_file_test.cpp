// Session files (ui/model/session_file.h): a round trip keeps every field, takes are written relative
// to the session and read back against its folder, bad files are refused with one line naming
// the file and the line, a missing take is reported while the rest reads. And the recent files
// (ui/model/recent_files.h), which never stop the editor from starting.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "engine/base/error.h"
#include "tests/test_data.h"
#include "ui/model/document_fields.h"
#include "ui/model/recent_files.h"
#include "ui/model/session_file.h"
#include "ui/model/weight_keys_edit.h"

using namespace mostyle;
using namespace mostyle::ui;
namespace fs = std::filesystem;

namespace {

// A session with every field away from its default.
SessionFile full_session() {
  SessionFile s;
  Document& d = s.document;
  d.parameters = {7, 0.25};
  DocumentControls& c = d.controls;
  c.mode = DecompositionMode::kPaper;
  c.per_part = true;
  c.component_regions = {BodyRegion::kLeftLeg, BodyRegion::kSpineAndHead, BodyRegion::kRightArm, BodyRegion::kLeftLeg};
  c.basic_motions = 3;
  c.basic_sparsities = {0.5, 0.2, 0.05};
  c.swap_level = 2;
  c.foot_lock = false;
  c.align.method = DtwMethod::kPaper;
  c.align.on = AlignOn::kHands;
  c.align.band = 12;
  c.align.slope.max_slope = 3;
  c.align.slope.open_ends = false;
  c.align.slope.end_penalty = 0.75;
  c.align.smoothing_frames = 4.5;
  c.timing_a = true;
  c.loop = true;
  c.residual = false;
  // Style over time: a walk that becomes tired over ten seconds, then exaggerated.
  c.keys = {WeightKey{0.0, {1.0, 0.0}}, WeightKey{10.0, {0.0, 1.0}}, WeightKey{12.345678901234, {-2.0 / 3.0, 5.0 / 3.0}}};
  // The ends of the sliders' ranges, as a float slider leaves them (1.3f is 1.2999999523...).
  d.layers = {TakeLayer{static_cast<double>(1.3f), {0.0, 0.125, std::nullopt, 0.3333333333333333}},
              TakeLayer{-0.5, {1.0, 0.875, std::nullopt, 0.6666666666666667}},
              TakeLayer{1.0 - static_cast<double>(1.3f) + 0.5, {}}};
  c.transfer = true;
  c.neutral = 0;
  c.content_neutral = true;
  c.ghosts = false;
  d.files = {"/data/day1/takes/walk_happy.bvh", "/data/shared/walk_marching.bvh"};
  d.overlay = true;
  SessionCamera camera;
  camera.target = {1.5f, 9.25f, -3.0f};
  camera.yaw = 0.65f;
  camera.pitch = 0.22f;
  camera.distance = 81.5f;
  camera.fov_y = 0.7f;
  s.camera = camera;
  s.playback.time_s = 1.2345;
  s.playback.playing = false;
  s.playback.speed = 0.5f;
  s.playback.loop = false;
  return s;
}

// The message parse_session throws, or "" when it reads.
std::string refusal(const std::string& text) {
  try {
    parse_session(text, "bad.mostyle");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string temp_folder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

}  // namespace

TEST_CASE("session files: format then parse gives the same session") {
  const SessionFile s = full_session();
  const std::string text = format_session(s, "/data/day1/monday.mostyle");
  // Takes relative to the session's folder; nothing of the folder itself in the file.
  CHECK_THAT(text, Catch::Contains("\"takes/walk_happy.bvh\"") && Catch::Contains("\"../shared/walk_marching.bvh\""));
  CHECK_THAT(text, !Catch::Contains("/data/day1"));
  CHECK(text.back() == '\n');
  const SessionFile back = parse_session(text, "/data/day1/monday.mostyle");
  CHECK(back.document == s.document);
  CHECK(back.document.layers == s.document.layers);
  CHECK_THAT(text, Catch::Contains("\"version\": 3") && Catch::Contains("\"component_weights\": [") &&
                       Catch::Contains("null"));
  CHECK(same_keys(back.document.controls.keys, s.document.controls.keys));  // to the last bit
  CHECK_THAT(text, Catch::Contains("\"keys\": [") && Catch::Contains("\"seconds\": 10.0"));
  REQUIRE(back.camera.has_value());
  CHECK(*back.camera == *s.camera);
  CHECK(back.playback.time_s == s.playback.time_s);
  CHECK(back.playback.playing == s.playback.playing);
  CHECK(back.playback.speed == s.playback.speed);
  CHECK(back.playback.loop == s.playback.loop);
  // Defaults too, and no camera stays no camera.
  const SessionFile plain;
  const SessionFile plain_back = parse_session(format_session(plain, "/x/s.mostyle"), "/x/s.mostyle");
  CHECK(plain_back.document == plain.document);
  CHECK_FALSE(plain_back.camera.has_value());
}

namespace {

// Sets a numeric field to v (a list: two numbers v); false for a field that is not numbers.
bool set_number(double& x, double v) { return x = v, true; }
bool set_number(int& x, double v) { return x = static_cast<int>(v), true; }
bool set_number(std::vector<double>& x, double v) { return x = {v, v}, true; }
bool set_number(std::vector<TakeLayer>& x, double v) { return x = {TakeLayer{v, {v, std::nullopt}}, TakeLayer{v, {}}}, true; }
template <typename T>
bool set_number(T&, double) {
  return false;
}

}  // namespace

TEST_CASE("session files: every field of the list reads back at both ends of its range, and not past them") {
  // A document where every range is at its widest: five basic-motion levels (swap_level 0 to 4).
  Document base;
  base.controls.basic_motions = static_cast<int>(kBasicMotionsRange.hi);
  int count = 0;
  document_fields(base, base, [&](const Field&, const auto&, const auto&) { ++count; });
  int numeric = 0;
  for (int target = 0; target < count; ++target) {
    for (const int end : {0, 1}) {
      for (const bool outside : {false, true}) {
        Document d = base;
        std::string key;
        bool is_number = false, saved = true;
        int i = 0;
        document_fields(d, d, [&](const Field& field, auto& x, auto&) {
          if (i++ != target || field.range.hi <= field.range.lo) return;
          const double step = outside ? (end == 0 ? -1.0 : 1.0) : 0.0;
          is_number = set_number(x, (end == 0 ? field.range.lo : field.range.hi) + step);
          key = field.key;
          saved = field.saved;
        });
        if (!is_number || !saved || key == "takes") continue;
        INFO(key << (end == 0 ? " at its low end" : " at its high end") << (outside ? ", one past it" : ""));
        const std::string text = format_session(SessionFile{d, std::nullopt, {}}, "/x/s.mostyle");
        if (outside) {
          const std::string message = refusal(text);
          CHECK_THAT(message, Catch::StartsWith("bad.mostyle:") && Catch::Contains(key) &&
                                  Catch::Contains("expected a"));
        } else {
          CHECK(parse_session(text, "/x/s.mostyle").document == d);
          numeric += end == 0;
        }
      }
    }
  }
  CHECK(numeric == 7);  // layers, k, sparsity, levels, level sparsities, swap level, the neutral
  // The sliders' own float ends read back (0.01f is 0.0099999998 as a double).
  Document slid;
  slid.parameters.sparsity = static_cast<double>(0.01f);
  set_layer_weights(slid, {static_cast<double>(1.5f), static_cast<double>(-0.5f)});
  CHECK(parse_session(format_session(SessionFile{slid, std::nullopt, {}}, "s.mostyle"), "s.mostyle").document == slid);
  // More takes than a palette holds.
  Document many;
  many.files.assign(static_cast<size_t>(kTakesRange.hi) + 1, "a.bvh");
  CHECK_THAT(refusal(format_session(SessionFile{many, std::nullopt, {}}, "s.mostyle")),
             Catch::Contains("takes: more than 16 takes"));
}

TEST_CASE("session files: takes resolve against the session's folder, wherever it moved") {
  const std::string text = R"({"version": 1, "takes": ["a.bvh", "sub/../b.bvh", "../c.bvh", "/abs/d.bvh"]})";
  const SessionFile s = parse_session(text, "/moved/here/s.mostyle");
  CHECK(s.document.files ==
        std::vector<std::string>{"/moved/here/a.bvh", "/moved/here/b.bvh", "/moved/c.bvh", "/abs/d.bvh"});
  // A session named without a folder: its takes are where it is.
  CHECK(parse_session(text, "s.mostyle").document.files[0] == "a.bvh");
  // Only "version" is needed; everything else keeps its default.
  const SessionFile minimal = parse_session("{\"version\": 1}", "m.mostyle");
  CHECK(minimal.document == Document());
  // A transfer written before the content could be its own neutral reads with its neutral take.
  const SessionFile old = parse_session(
      R"({"version": 1, "controls": {"palette": {"transfer": true, "neutral": 2, "strengths": [0, 1, 0.5]}}})",
      "old.mostyle");
  CHECK(old.document.controls.transfer);
  CHECK(old.document.controls.neutral == 2);
  CHECK_FALSE(old.document.controls.content_neutral);
  CHECK_FALSE(minimal.camera.has_value());
  CHECK(is_session_path("a/day.mostyle"));
  CHECK(is_session_path("DAY.MOSTYLE"));
  CHECK_FALSE(is_session_path("walk.bvh"));
  CHECK_FALSE(is_session_path("mostyle"));
}

TEST_CASE("session files: version 1 files read a pair's alpha or a palette's weights into the weights") {
  // A pair as version 1 wrote it: alpha 0.3 is the weights (0.7, 0.3); the palette's weights
  // (empty) are not the pair's.
  const std::string pair = R"({
  "version": 1,
  "takes": ["happy.bvh", "marching.bvh"],
  "parameters": {"alpha": 0.3, "components": 12, "sparsity": 0.15},
  "controls": {
    "per_component": true,
    "component_alpha": [0.3, 1.0, 0.0],
    "palette": {"weights": [], "per_part": false, "part_weights": [], "strengths": [], "ghosts": false}
  }
})";
  const Document p = parse_session(pair, "/day/pair.mostyle").document;
  CHECK(p.files == std::vector<std::string>{"/day/happy.bvh", "/day/marching.bvh"});
  CHECK(layer_weights(p) == std::vector<double>{0.7, 0.3});
  CHECK(pair_alpha(p) == 0.3);
  CHECK(p.parameters.components == 12);
  CHECK(p.parameters.sparsity == 0.15);
  CHECK(p.controls.per_part);
  CHECK(p.layers[0].component_weights == std::vector<std::optional<double>>{0.7, 0.0, 1.0});
  CHECK(p.layers[1].component_weights == std::vector<std::optional<double>>{0.3, 1.0, 0.0});
  CHECK(p.controls.component_regions.empty());  // kept by index once a decomposition is in
  CHECK(p.controls.ghosts);                      // a pair's takes stood beside its result
  // A palette as version 1 wrote it: its weights; the alpha written beside them was not its.
  const std::string palette = R"({
  "version": 1,
  "takes": ["neutral.bvh", "happy.bvh", "sad.bvh", "proud.bvh"],
  "parameters": {"alpha": 0.5, "components": 10, "sparsity": 0.1},
  "controls": {
    "palette": {"weights": [0.4, 0.3, 0.2, 0.1], "per_part": true, "part_weights": [[1, 0, 0, 0], [], []],
                "transfer": false, "content": 0, "neutral": 2, "strengths": [1, 1, 1, 1]}
  }
})";
  const Document m = parse_session(palette, "/day/palette.mostyle").document;
  CHECK(m.files.size() == 4);
  CHECK(layer_weights(m) == std::vector<double>{0.4, 0.3, 0.2, 0.1});
  CHECK(m.controls.per_part);
  CHECK(m.controls.neutral == 2);
  CHECK_FALSE(m.controls.ghosts);
  // The legs' row by body region: both legs from the first take, the rest following the weights.
  REQUIRE(m.controls.component_regions.size() == 5);
  for (size_t g = 0; g < 5; ++g) {
    const bool leg = part_covers(BodyPart::kLegs, m.controls.component_regions[g]);
    for (size_t i = 0; i < 4; ++i)
      CHECK(m.layers[i].component_weights[g] == (leg ? std::optional<double>(i == 0 ? 1.0 : 0.0) : std::nullopt));
  }
  // Written again, they are version 3: the layers at the top, neither alpha nor the palette's.
  for (const Document& d : {p, m}) {
    const std::string text = format_session(SessionFile{d, std::nullopt, {}}, "/day/s.mostyle");
    CHECK_THAT(text, Catch::Contains("\"version\": 3") && Catch::Contains("\"layers\": [") &&
                         !Catch::Contains("\"alpha\"") && !Catch::Contains("\"palette\""));
    CHECK(parse_session(text, "/day/s.mostyle").document == d);
  }
  // Without the weights its takes use (a pair's alpha, a palette's weights): the defaults, equal
  // weights once the takes are in.
  CHECK(parse_session(R"({"version": 1, "takes": ["a.bvh", "b.bvh"], "controls": {"palette": {"weights": [0.2, 0.8]}}})",
                      "s.mostyle")
            .document.layers.empty());
  CHECK(parse_session(R"({"version": 1, "takes": ["a.bvh", "b.bvh", "c.bvh"], "parameters": {"alpha": 0.9}})",
                      "s.mostyle")
            .document.layers.empty());
  // No takes: the alpha's weights are not one per take (none): the defaults.
  CHECK(parse_session(R"({"version": 1, "parameters": {"alpha": 0.25}})", "s.mostyle").document.layers.empty());
}

TEST_CASE("session files: version 2 sessions the editor wrote read into the layers") {
  // Written by the editor before the layers (tests/ui/model/sessions/): a pair with an alpha per
  // component, a palette's mix with the legs from one take and the spine from another, and its
  // transfer with strengths.
  const std::string dir = test::asset("../tests/ui/model/sessions");
  const Document pair = read_session_file(dir + "/version_2_pair.mostyle").document;
  CHECK(fs::path(pair.files[1]).filename() == "cmu142_walk_marching.bvh");
  CHECK(layer_weights(pair) == std::vector<double>{0.7, 0.3});
  CHECK(pair.controls.per_part);
  CHECK(pair.controls.timing_a);
  CHECK(pair.controls.ghosts);
  const std::vector<double> alphas{0.3, 0.9, 0.3, 0.0, 0.3, 0.6};
  REQUIRE(pair.layers[1].component_weights.size() == alphas.size());
  for (size_t c = 0; c < alphas.size(); ++c) {
    CHECK(pair.layers[0].component_weights[c] == 1.0 - alphas[c]);
    CHECK(pair.layers[1].component_weights[c] == alphas[c]);
  }
  const Document palette = read_session_file(dir + "/version_2_palette.mostyle").document;
  CHECK(layer_weights(palette) == std::vector<double>{0.5, 0.2, 0.3});
  CHECK(palette.controls.per_part);
  CHECK_FALSE(palette.controls.transfer);
  CHECK(palette.controls.ghosts);
  REQUIRE(palette.controls.component_regions.size() == 5);
  for (size_t g = 0; g < 5; ++g) {
    const BodyRegion region = palette.controls.component_regions[g];
    const int from = part_covers(BodyPart::kLegs, region) ? 1 : part_covers(BodyPart::kSpine, region) ? 2 : -1;
    for (size_t i = 0; i < 3; ++i)
      CHECK(palette.layers[i].component_weights[g] ==
            (from < 0 ? std::nullopt : std::optional<double>(static_cast<int>(i) == from ? 1.0 : 0.0)));
  }
  // The transfer: its layers' weights are the strengths it mixed.
  const Document transfer = read_session_file(dir + "/version_2_transfer.mostyle").document;
  CHECK(transfer.controls.transfer);
  CHECK(transfer.controls.neutral == 1);
  CHECK_FALSE(transfer.controls.content_neutral);
  CHECK(layer_weights(transfer) == std::vector<double>{1.0, 0.5, 0.25});
}

TEST_CASE("session files: a bad file is refused with one line naming the file and the line") {
  struct Case {
    std::string text;
    int line;
    const char* says;
  };
  const std::vector<Case> cases = {
      {"", 1, "not valid JSON"},
      {"not json at all", 1, "not valid JSON"},
      {"{\n  \"version\": 1,\n  \"parameters\": {\"alpha\": }\n}", 3, "not valid JSON"},
      {"[1, 2]", 1, "expected a mostyle session"},
      {"{\n  \"takes\": []\n}", 1, "no \"version\""},
      {"{\n  \"version\": \"1\"\n}", 2, "version: expected a whole number"},
      {"{\n  \"version\": 4\n}", 2, "version 4 is not one this mostyle reads (it reads versions 1 to 3)"},
      {"{\n  \"version\": 0\n}", 2, "version 0 is not one this mostyle reads"},
      {"{\n  \"version\": 1,\n  \"parameters\": {\n    \"alpha\": \"half\"\n  }\n}", 4,
       "parameters.alpha: expected a number from -0.5 to 1.5, found the string 'half'"},
      {"{\"version\": 1,\n\"parameters\": {\"alpha\": 1.6}}", 2, "parameters.alpha: expected a number from -0.5 to 1.5, found 1.6"},
      {"{\"version\": 1,\n\"parameters\": {\n\"components\": 2.5}}", 3, "parameters.components: expected a whole number"},
      {"{\"version\": 1,\n\"parameters\": {\n\"sparsity\": 0}}", 3, "parameters.sparsity: expected a number from 0.01 to 1, found 0"},
      {"{\"version\": 1,\n\"parameters\": {\n\n\"alpah\": 0.5}}", 4, "unknown key 'alpah' in parameters"},
      {"{\"version\": 1,\n\"extra\": true}", 2, "unknown key 'extra'"},
      {"{\"version\": 1,\n\"takes\": \"a.bvh\"}", 2, "takes: expected an array"},
      {"{\"version\": 1,\n\"takes\": [\n\"a.bvh\",\n7]}", 4, "takes[1]: expected a string, found 7"},
      {"{\"version\": 1,\n\"takes\": [\"\"]}", 2, "takes[0]: an empty file name"},
      {"{\"version\": 1,\n\"controls\": {\"align\": {\n\"on\": \"elbow\"}}}", 3, "controls.align.on: expected an alignment feature auto, left-foot"},
      {"{\"version\": 1,\n\"controls\": {\"mode\": \"fast\"}}", 2, "controls.mode: expected \"shared\" or \"paper\""},
      {"{\"version\": 1,\n\"controls\": {\"component_alpha\": [0.5,\n-1]}}", 3, "controls.component_alpha[1]"},
      {"{\"version\": 1,\n\"controls\": {\"basic_motions\": 2, \"swap_level\": 2}}", 2, "controls.swap_level"},
      {"{\"version\": 1,\n\"camera\": {\n\"target\": [1, 2]}}", 3, "camera.target: expected an array of 3 numbers"},
      {"{\"version\": 1,\n\"camera\": {\"distance\": 0}}", 2, "camera.distance"},
      {"{\"version\": 1,\n\"playback\": {\"playing\": \"yes\"}}", 2, "playback.playing: expected true or false"},
      {"{\"version\": 1,\n\"playback\": {\n\"time_s\": 1e400}}", 3, "a number too large"},
      {"{\"version\": 1,\n\"view\": []}", 2, "view: expected an object"},
      {"{\"version\": 1,\n\"controls\": {\"palette\": 3}}", 2, "controls.palette: expected an object"},
      {"{\"version\": 1,\n\"controls\": {\"palette\": {\n\"wieghts\": []}}}", 3,
       "unknown key 'wieghts' in controls.palette (known: per_part"},
      {"{\"version\": 3,\n\"controls\": {\"palette\": {}}}", 2, "unknown key 'palette' in controls"},
      {"{\"version\": 3,\n\"weights\": [0.5, 0.5]}", 2, "unknown key 'weights'"},
      {"{\"version\": 3,\n\"layers\": [{\"weight\": 0.5},\n{\"weigth\": 0.5}]}", 3, "unknown key 'weigth' in layers[1]"},
      {"{\"version\": 3,\n\"layers\": [\n{\"component_weights\": [0.5]}]}", 3, "layers[0]: a layer needs \"weight\""},
      {"{\"version\": 3,\n\"layers\": [{\"weight\": 0.5, \"component_weights\": [\n\"x\"]}]}", 3,
       "layers[0].component_weights[0]: expected a number"},
      {"{\"version\": 3,\n\"controls\": {\"component_regions\": [\n\"tail\"]}}", 3,
       "controls.component_regions[0]: expected a body region"},
      {"{\"version\": 1,\n\"controls\": {\n\"selected_component\": 2}}", 3,
       "unknown key 'selected_component' in controls"},  // where one looks: not kept
      {"{\"version\": 1,\n\"parameters\": {\n\"components\": 41}}", 3,
       "parameters.components: expected a whole number from 1 to 40, found 41"},
      // Beyond what the palette's sliders allow (-0.5 to 1.5; strengths -1 to 2).
      {"{\"version\": 1,\n\"controls\": {\"palette\": {\n\"weights\": [1.6, -0.6]}}}", 3,
       "controls.palette.weights[0]: expected a number from -0.5 to 1.5, found 1.6"},
      {"{\"version\": 1,\n\"controls\": {\"palette\": {\"strengths\": [\n0, 2.5]}}}", 3,
       "controls.palette.strengths[1]"},
      // Version 2: one weight per take at the top; alpha and the palette's weights are version 1's.
      {"{\"version\": 2,\n\"weights\": [1.6, -0.6]}", 2, "weights[0]: expected a number from -0.5 to 1.5, found 1.6"},
      {"{\"version\": 2,\n\"weights\": 0.5}", 2, "weights: expected an array"},
      {"{\"version\": 2,\n\"parameters\": {\n\"alpha\": 0.5}}", 3,
       "unknown key 'alpha' in parameters (known: components, sparsity)"},
      {"{\"version\": 2,\n\"controls\": {\"palette\": {\n\"weights\": [0.5, 0.5]}}}", 3,
       "unknown key 'weights' in controls.palette"},
      {"{\"version\": 2,\n\"controls\": {\"palette\": {\n\"part_weights\": [[2, -1]]}}}", 3,
       "controls.palette.part_weights[0][0]: expected a number from -0.5 to 1.5, found 2"},
      {"{\"version\": 1,\n\"weights\": [0.5, 0.5]}", 2, "unknown key 'weights' in a version 1 session"},
      // Keys: each a time and a weight per take, in order of time, as many weights in each.
      {"{\"version\": 1,\n\"controls\": {\"keys\": 3}}", 2, "controls.keys: expected an array of keys"},
      {"{\"version\": 1,\n\"controls\": {\"keys\": [\n{\"seconds\": 1}]}}", 3,
       "controls.keys[0]: a key needs \"seconds\" and \"weights\""},
      {"{\"version\": 1,\n\"controls\": {\"keys\": [\n{\"seconds\": 1, \"weights\": [0, 1], \"ease\": 1}]}}", 3,
       "unknown key 'ease' in controls.keys[0]"},
      {"{\"version\": 1,\n\"controls\": {\"keys\": [{\"weights\": [0, 1],\n\"seconds\": -1}]}}", 3,
       "controls.keys[0].seconds: expected a number from 0"},
      {"{\"version\": 1,\n\"controls\": {\"keys\": [{\"seconds\": 0, \"weights\": [\n-40, 1]}]}}", 3,
       "controls.keys[0].weights[0]: expected a number from -32 to 17, found -40"},
      {"{\"version\": 1,\n\"controls\": {\"keys\": [\n{\"seconds\": 2, \"weights\": [0.5, 0.5]},\n"
       "{\"seconds\": 1, \"weights\": [0.5, 0.5]}]}}",
       4, "controls.keys: expected keys in order of time: key 2 (at 1 s) does not come after key 1 (at 2 s)"},
      {"{\"version\": 1,\n\"controls\": {\"keys\": [\n{\"seconds\": 0, \"weights\": [1, 0]},\n"
       "{\"seconds\": 5, \"weights\": [0.5, 0.5]},\n{\"seconds\": 9, \"weights\": [0.2, 0.3, 0.5]}]}}",
       5, "expected 2 weights, one per take, in key 3 (at 9 s), found 3"},
  };
  for (const Case& c : cases) {
    INFO(c.text);
    const std::string message = refusal(c.text);
    CHECK_THAT(message, Catch::StartsWith("bad.mostyle:" + std::to_string(c.line) + ": "));
    CHECK_THAT(message, Catch::Contains(c.says));
    CHECK(message.find('\n') == std::string::npos);
  }
}

TEST_CASE("session files: a missing take is reported, and the rest of the session reads") {
  const std::string dir = temp_folder("mostyle_session_test_missing");
  const std::string path = dir + "/day.mostyle";
  SessionFile s = full_session();
  s.document.files = {test::asset("motions/cmu142_walk_happy.bvh"), dir + "/gone.bvh"};
  write_session_file(path, s);
  const SessionFile back = read_session_file(path);
  CHECK(back.document == s.document);  // every parameter, the takes as they were named
  CHECK(*back.camera == *s.camera);
  const std::vector<std::string> missing = missing_takes(back.document);
  CHECK(missing == std::vector<std::string>{dir + "/gone.bvh"});
  const std::string message = missing_takes_message(path, missing, true);
  CHECK_THAT(message, Catch::StartsWith(path + ": cannot find the take ") && Catch::Contains("gone.bvh") &&
                          Catch::Contains("other takes") && Catch::Contains("left as it is"));
  CHECK(message.find('\n') == std::string::npos);
  CHECK_THAT(missing_takes_message(path, missing, false), Catch::Contains("loaded before stay"));
  CHECK(missing_takes_message(path, {}, true).empty());
  // Writes are atomic: a failed one leaves the file as it was.
  CHECK_THROWS_AS(write_session_file(dir + "/no/such/folder/day.mostyle", s), InputError);
  CHECK(read_session_file(path).document == s.document);
  CHECK_THROWS_WITH(read_session_file(dir + "/none.mostyle"), Catch::Contains("none.mostyle"));
  fs::remove_all(dir);
}

TEST_CASE("recent files: newest first, capped, and a broken file reads as empty") {
  std::vector<std::string> list;
  for (int i = 0; i < 12; ++i) remember(list, "/t/" + std::to_string(i) + ".bvh", kRecentTakes);
  CHECK(list.size() == kRecentTakes);
  CHECK(list.front() == "/t/11.bvh");
  remember(list, "/t/8.bvh", kRecentTakes);
  CHECK(list.front() == "/t/8.bvh");
  CHECK(list.size() == kRecentTakes);
  remember(list, "", kRecentTakes);
  CHECK(list.front() == "/t/8.bvh");

  RecentFiles r;
  r.takes = {"/t/a.bvh", "/t/b.bvh"};
  r.sessions = {"/s/day.mostyle"};
  const RecentFiles back = parse_recent_files(format_recent_files(r));
  CHECK(back.takes == r.takes);
  CHECK(back.sessions == r.sessions);
  for (const char* broken : {"", "{", "[]", "{\"takes\": 3}", "{\"takes\": [1, \"\", \"/t/a.bvh\"]}", "1e400"}) {
    INFO(broken);
    const RecentFiles b = parse_recent_files(broken);
    CHECK(b.sessions.empty());
    CHECK(b.takes.size() <= 1);
  }

  const std::string dir = temp_folder("mostyle_recent_test");
  const std::string path = dir + "/config/mostyle/recent.json";
  CHECK(read_recent_files(path).takes.empty());  // not there yet
  write_recent_files(path, r);                   // makes its folder
  CHECK(read_recent_files(path).takes == r.takes);
  write_text(path, "{\"takes\": [\"/t/a.bvh\",");  // broken by hand
  CHECK(read_recent_files(path).takes.empty());
  CHECK(read_recent_files("").takes.empty());
  fs::remove_all(dir);
}

TEST_CASE("recent files live in XDG_CONFIG_HOME, else HOME/.config") {
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  const char* home = std::getenv("HOME");
  const std::string saved_xdg = xdg ? xdg : "", saved_home = home ? home : "";
  setenv("XDG_CONFIG_HOME", "/cfg", 1);
  CHECK(recent_files_path() == "/cfg/mostyle/recent.json");
  unsetenv("XDG_CONFIG_HOME");
  setenv("HOME", "/home/animator", 1);
  CHECK(recent_files_path() == "/home/animator/.config/mostyle/recent.json");
  unsetenv("HOME");
  CHECK(recent_files_path().empty());
  if (xdg) setenv("XDG_CONFIG_HOME", saved_xdg.c_str(), 1);
  if (home) setenv("HOME", saved_home.c_str(), 1);
}
