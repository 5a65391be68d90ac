// The blending editor's panels and its link to the engine (ui/model/engine_link.h), run as ImGui
// frames with no window: the panels build over a loaded pair, alpha moves the blend in the same
// frame, and a failed load shows its sentence while the previous pair stays.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <imgui_internal.h>  // ImGui::FindWindowByName

#include "tests/test_data.h"
#include "tests/ui/imgui_frame.h"
#include "tests/ui/loaded_takes.h"
#include "ui/model/dtw_image.h"
#include "ui/panels/files_panel.h"
#include "ui/panels/layout.h"
#include "ui/model/document_mix.h"
#include "ui/panels/metrics_panel.h"
#include "engine/post/speed_limit.h"

using namespace mostyle;
using namespace mostyle::ui;
using test::all_panels;
using test::LoadedTakes;

namespace {

constexpr double kExactSliding = 1e-9;  // file units per second: a weighted sum, rounding only

// Distance between the same joint of two takes at one frame.
double joint_distance(const ShownMotion& a, const ShownMotion& b, int frame, int joint) {
  return (a.positions.row(frame).segment<3>(3 * joint) - b.positions.row(frame).segment<3>(3 * joint)).norm();
}

}  // namespace

TEST_CASE("the session turns a loaded pair into A, B and the blend, in step on the blend's timeline") {
  LoadedTakes s;
  REQUIRE(s.engine.error().empty());
  REQUIRE(s.state.shown.size() == 3);
  const PreparedTakes& p = *s.engine.snapshot().prepared;
  REQUIRE(s.engine.result() != nullptr);
  for (const ShownMotion& t : s.state.shown) {
    CHECK(t.ok());
    CHECK(t.frames() == s.engine.result()->motion.world.rows());  // all three in step on the blend's timeline
    CHECK(t.positions.cols() == p.takes[0].world.cols());
    CHECK(t.rate() == p.fps);
    CHECK(t.parents == p.parents);
  }
  REQUIRE(s.engine.result() != nullptr);
  CHECK(s.state.shown[result_index(2)].positions.rows() == s.engine.result()->motion.world.rows());
  const DtwCostImage img = dtw_cost_image(*s.engine.takes());
  CHECK(img.rows > 0);
  CHECK(img.rows <= DtwCostImage::kMaxCells);
  CHECK(img.cost.maxCoeff() == Approx(1.0));
}

TEST_CASE("the panels build over a loaded pair, with a component picked and in both modes") {
  LoadedTakes s;
  test::HeadlessImGui imgui;
  auto panels = all_panels(s.engine);
  for (int frame = 0; frame < 6; ++frame) {
    if (frame == 2) s.state.document.controls.selected_component = 1;
    if (frame == 4) s.state.document.controls.per_part = true;
    imgui.begin_frame();
    s.engine.poll(s.state);
    for (auto& panel : panels) panel->draw(s.state);
    s.engine.sync(s.state);
    CHECK(imgui.end_frame() > 1000);
  }
  // The picked component lights up joints of the blend skeleton only.
  const auto& highlights = s.state.shown[result_index(2)].highlights;
  REQUIRE(highlights.size() == s.state.shown[result_index(2)].parents.size());
  int lit = 0;
  for (const auto& h : highlights) lit += h.a > 0.0f ? 1 : 0;
  CHECK(lit > 0);
  CHECK(s.state.shown[0].highlights.empty());

  // Paper mode with basic motions: a re-decomposition on the worker, panels still draw.
  s.state.document.controls.mode = DecompositionMode::kPaper;
  s.state.document.controls.basic_motions = 2;
  s.engine.wait_idle(s.state);
  CHECK(s.engine.error().empty());
  CHECK(s.engine.snapshot().decomposed->params.mode == DecompositionMode::kPaper);
  imgui.begin_frame();
  for (auto& panel : panels) panel->draw(s.state);
  s.engine.sync(s.state);
  CHECK(imgui.end_frame() > 1000);
  CHECK(s.engine.result_error().empty());
}

TEST_CASE("moving alpha changes the blended pose in the same frame, from A towards B") {
  LoadedTakes s;
  s.state.document.overlay = true;  // no lateral offsets: the takes can be compared
  const int frame = s.state.shown[0].frames() / 2;
  set_pair_alpha(s.state.document, 0.0);
  s.engine.sync(s.state);
  const Eigen::MatrixXd at_a = s.state.shown[result_index(2)].positions;
  set_pair_alpha(s.state.document, 1.0);
  s.engine.sync(s.state);  // no worker round trip
  const Eigen::MatrixXd at_b = s.state.shown[result_index(2)].positions;
  CHECK((at_a - at_b).norm() > 1.0);
  CHECK(s.engine.result_view().mix_ms() < 1000.0);  // sanity only; speed is measured in tests/bench
  // A wrist at alpha 0 is nearer A's than B's, and at alpha 1 the other way round.
  const int wrist = static_cast<int>(s.state.shown[0].parents.size()) - 1;
  ShownMotion blend_a = s.state.shown[result_index(2)], blend_b = s.state.shown[result_index(2)];
  blend_a.positions = at_a;
  blend_b.positions = at_b;
  double to_a = 0, to_b = 0, back_a = 0, back_b = 0;
  for (int j = 0; j <= wrist; ++j) {
    to_a += joint_distance(blend_a, s.state.shown[0], frame, j);
    to_b += joint_distance(blend_a, s.state.shown[1], frame, j);
    back_a += joint_distance(blend_b, s.state.shown[0], frame, j);
    back_b += joint_distance(blend_b, s.state.shown[1], frame, j);
  }
  CHECK(to_a < to_b);
  CHECK(back_b < back_a);
}

TEST_CASE("a failing load shows its error and keeps the previous pair") {
  LoadedTakes s;
  const auto before = s.engine.snapshot().prepared;
  const Eigen::MatrixXd blend_before = s.state.shown[result_index(2)].positions;
  s.engine.load("/nonexistent/walk.bvh", test::asset("motions/cmu142_walk_marching.bvh"));
  s.engine.wait_idle(s.state);
  CHECK_THAT(s.engine.error(), Catch::Contains("/nonexistent/walk.bvh"));
  CHECK(s.engine.snapshot().prepared == before);
  REQUIRE(s.state.shown.size() == 3);
  CHECK(s.state.shown[result_index(2)].positions == blend_before);
  // The panels still draw (the files panel shows the sentence); the mistyped path never joins the
  // recent files, the pair that loaded is there.
  test::HeadlessImGui imgui;
  auto panels = all_panels(s.engine);
  imgui.begin_frame();
  for (auto& panel : panels) panel->draw(s.state);
  CHECK(imgui.end_frame() > 1000);
  const std::vector<std::string>& recent = s.state.recent.takes;
  CHECK(std::find(recent.begin(), recent.end(), "/nonexistent/walk.bvh") == recent.end());
  REQUIRE_FALSE(recent.empty());
  CHECK(recent.front() == test::asset("motions/cmu142_walk_happy.bvh"));
  // And a good pair after it clears the error.
  s.engine.load(test::asset("motions/cmu142_walk_joy.bvh"), test::asset("motions/cmu142_walk_happy.bvh"));
  s.engine.wait_idle(s.state);
  CHECK(s.engine.error().empty());
  CHECK(s.engine.snapshot().prepared != before);
  CHECK(s.state.shown.size() == 3);
}

TEST_CASE("export writes the blend as BVH or says why not, in the files panel") {
  LoadedTakes s;
  test::HeadlessImGui imgui;
  FilesPanel files(s.engine, test::asset("motions"));
  auto frame = [&]() {
    imgui.begin_frame();
    files.draw(s.state);
    imgui.end_frame();
  };
  const std::string out = (std::filesystem::temp_directory_path() / "mostyle_ui_export_test.bvh").string();
  std::filesystem::remove(out);
  ExportDialog& dialog = files.export_dialog();
  frame();
  std::snprintf(dialog.settings().path, sizeof dialog.settings().path, "%s", out.c_str());
  REQUIRE(dialog.press_export() == ExportDialog::Pressed::kStarted);
  dialog.job().wait();
  frame();
  CHECK(std::filesystem::exists(out));
  CHECK(dialog.status().ok);
  CHECK_THAT(dialog.status().message, Catch::Contains("mostyle_ui_export_test.bvh"));
  std::filesystem::remove(out);
  std::snprintf(dialog.settings().path, sizeof dialog.settings().path, "%s", "/nonexistent/dir/out.bvh");
  REQUIRE(dialog.press_export() == ExportDialog::Pressed::kStarted);
  dialog.job().wait();
  frame();
  CHECK_FALSE(dialog.status().message.empty());
  CHECK_FALSE(dialog.status().ok);
}

TEST_CASE("files dropped on the window load as the takes (two or more) or as one more take (one)") {
  LoadedTakes s;
  test::HeadlessImGui imgui;
  FilesPanel files(s.engine, test::asset("motions"));
  const std::string joy = test::asset("motions/cmu142_walk_joy.bvh");
  s.state.dropped = {joy};
  imgui.begin_frame();
  files.draw(s.state);
  imgui.end_frame();
  CHECK(s.state.dropped.empty());
  CHECK(s.engine.requested_files() == std::vector<std::string>{test::asset("motions/cmu142_walk_happy.bvh"),
                                                                test::asset("motions/cmu142_walk_marching.bvh"), joy});
  s.engine.wait_idle(s.state);
  CHECK(s.engine.error().empty());
  CHECK(s.engine.snapshot().paths[2] == joy);
  CHECK(s.state.shown.size() == 4);
  CHECK_THAT(s.state.shown[2].label, Catch::Contains("joy"));
  // Two dropped: the new takes, a pair again.
  s.state.dropped = {joy, test::asset("motions/cmu142_walk_happy.bvh")};
  imgui.begin_frame();
  files.draw(s.state);
  imgui.end_frame();
  s.engine.wait_idle(s.state);
  CHECK(s.engine.snapshot().paths[0] == joy);
  CHECK(s.state.shown.size() == 3);
}

TEST_CASE("space plays and pauses, the arrow keys step one frame") {
  LoadedTakes loaded;
  test::HeadlessImGui imgui;
  ImGuiIO& io = ImGui::GetIO();
  io.KeyMap[ImGuiKey_Space] = 1;
  io.KeyMap[ImGuiKey_RightArrow] = 2;
  io.KeyMap[ImGuiKey_LeftArrow] = 3;
  PlaybackPanel panel;
  EditorState& state = loaded.state;
  state.playback.playing = false;
  state.playback.time_s = 0.0;
  const ShownMotion* reference = state.reference_take();
  REQUIRE(reference != nullptr);
  auto press = [&](int key) {
    io.KeysDown[key] = true;
    imgui.begin_frame();
    panel.draw(state);
    imgui.end_frame();
    io.KeysDown[key] = false;
    imgui.begin_frame();
    panel.draw(state);
    imgui.end_frame();
  };
  press(1);
  CHECK(state.playback.playing);
  press(1);
  CHECK_FALSE(state.playback.playing);
  press(2);
  press(2);
  CHECK(frame_at(*reference, state.playback.time_s) == 2);
  press(3);
  CHECK(frame_at(*reference, state.playback.time_s) == 1);
}

TEST_CASE("timing, loop and alignment controls reach the blend and the alignment") {
  LoadedTakes s;
  REQUIRE(s.engine.result() != nullptr);
  const PreparedTakes& p = *s.engine.snapshot().prepared;
  const Alignment& al = p.takes[1].alignment;
  DocumentControls& c = s.state.document.controls;
  // alpha 0: A's timing, as long as A's matched range; with A's timing kept at alpha 1 too.
  set_pair_alpha(s.state.document, 0.0);
  s.engine.sync(s.state);
  const Eigen::Index at_a = s.engine.result()->motion.world.rows();
  // A's matched range in its file's frames (its own timeline plays its cycles again where B has more).
  const Eigen::VectorXd a_ends = frames_in_take(p.takes[0], Eigen::Vector2d(al.a_first, al.a_last));
  CHECK(at_a == std::lround(a_ends[1] - a_ends[0]) + 1);
  set_pair_alpha(s.state.document, 1.0);
  s.engine.sync(s.state);
  CHECK(s.engine.result()->motion.world.rows() == al.b_last - al.b_first + 1);
  c.timing_a = true;
  s.engine.sync(s.state);
  CHECK(s.engine.result()->motion.world.rows() == at_a);
  for (const ShownMotion& t : s.state.shown) CHECK(t.frames() == at_a);  // A and B follow the blend's timeline
  // A seamless loop: whole cycles, every take cut to it.
  c.timing_a = false;
  c.loop = true;
  set_pair_alpha(s.state.document, 0.5);
  s.engine.sync(s.state);
  REQUIRE(s.engine.result() != nullptr);
  CHECK(s.engine.result()->motion.loop.cycles >= 1);
  CHECK(s.engine.result()->motion.loop.cycles <= kLoopMaxCycles);
  for (const ShownMotion& t : s.state.shown) CHECK(t.frames() == s.engine.result()->motion.loop.frames());
  // Aligning on the body re-prepares the pair on the worker.
  c.loop = false;
  c.align.on = AlignOn::kBody;
  s.engine.wait_idle(s.state);
  REQUIRE(s.engine.snapshot().prepared != nullptr);
  CHECK(s.engine.snapshot().prepared->takes[1].alignment.feature.on == AlignOn::kBody);
  CHECK(s.engine.error().empty());
  // The panels draw over it, warnings and quality strip included.
  test::HeadlessImGui imgui;
  auto panels = all_panels(s.engine);
  for (int frame = 0; frame < 3; ++frame) {
    imgui.begin_frame();
    for (auto& panel : panels) panel->draw(s.state);
    CHECK(imgui.end_frame() > 0);
  }
}

TEST_CASE("files panel: a take is named by its role, and one take is replaced or added") {
  CHECK(take_role(0, 2) == "A");
  CHECK(take_role(1, 2) == "B");
  CHECK(take_role(0, 4) == "1");
  CHECK(take_role(3, 4) == "4");
  const std::vector<std::string> palette = {"n.bvh", "t.bvh", "o.bvh", "p.bvh"};
  CHECK(with_take(palette, 0, "x.bvh") == std::vector<std::string>{"x.bvh", "t.bvh", "o.bvh", "p.bvh"});
  CHECK(with_take(palette, 4, "x.bvh") == std::vector<std::string>{"n.bvh", "t.bvh", "o.bvh", "p.bvh", "x.bvh"});
  CHECK(with_take({"a.bvh", "b.bvh"}, 2, "x.bvh") == std::vector<std::string>{"a.bvh", "b.bvh", "x.bvh"});
  CHECK(with_take({"a.bvh", ""}, 2, "x.bvh") == std::vector<std::string>{"a.bvh", "x.bvh"});  // A with itself
}

TEST_CASE("files panel: a file dropped on a palette is one more take, and a load error moves nothing") {
  LoadedTakes s;
  test::HeadlessImGui imgui;
  FilesPanel files(s.engine, test::asset("motions"));
  auto draw = [&] {
    for (int i = 0; i < 2; ++i) {
      imgui.begin_frame();
      files.draw(s.state);
      imgui.end_frame();
    }
  };
  auto content_height = [] {
    const ImGuiWindow* w = ImGui::FindWindowByName(panel_title(PanelId::kFiles));
    REQUIRE(w != nullptr);
    return w->ContentSize.y;
  };
  draw();
  const float height = content_height();
  // A load that fails: its sentence appears in the messages' own space; the fields and what is
  // under them stay where they were.
  s.engine.load("/nonexistent/walk.bvh", test::asset("motions/cmu142_walk_marching.bvh"));
  s.engine.wait_idle(s.state);
  REQUIRE_FALSE(s.engine.error().empty());
  CHECK_THAT(s.engine.error(), Catch::Contains("/nonexistent/walk.bvh"));
  draw();
  CHECK(content_height() == height);

  const std::vector<std::string> palette = {test::asset("motions/cmu142_walk_happy.bvh"),
                                            test::asset("motions/cmu142_walk_marching.bvh"),
                                            test::asset("motions/cmu142_walk_joy.bvh")};
  s.engine.load_files(palette);
  s.engine.wait_idle(s.state);
  REQUIRE(s.engine.takes() != nullptr);
  draw();
  const std::string clumsy = test::asset("motions/cmu142_walk_clumsy.bvh");
  s.state.dropped = {clumsy};
  draw();
  std::vector<std::string> four = palette;
  four.push_back(clumsy);
  CHECK(s.engine.requested_files() == four);  // added, not a pair of the dropped file
  s.engine.wait_idle(s.state);
  REQUIRE(s.engine.takes() != nullptr);
  CHECK(s.engine.takes()->size() == 4);
  // The metrics speak of the palette: each take's fit error and foot sliding, the mix's bones.
  const Metrics m = gather_metrics(s.engine, s.state.document.controls.transfer);
  CHECK(m.result == "mix");
  REQUIRE(m.measures.takes.size() == 4);
  REQUIRE(m.take_names.size() == 4);
  for (const TakeMeasures& t : m.measures.takes) {
    REQUIRE(t.fit_error);
    CHECK(*t.fit_error >= 0.0);
    CHECK(t.planted_speed >= 0.0);
    CHECK(t.fastest_joint > 0.0);
  }
  CHECK(m.take_names[3] == "clumsy");  // what tells the takes apart fits the narrow column
  REQUIRE(m.measures.result);
  const ResultMeasures& r = *m.measures.result;
  CHECK(r.limb_length_max_error >= 0.0);
  CHECK(r.planted_cleaned >= 0.0);
  // The mix's planted feet, measured as the takes' are, against the takes' own weighted.
  CHECK(r.planted_cleaned <= r.planted_raw);
  double least = m.measures.takes[0].planted_speed, most = least, fastest = 0.0;
  for (const TakeMeasures& t : m.measures.takes) {
    least = std::min(least, t.planted_speed);
    most = std::max(most, t.planted_speed);
    fastest = std::max(fastest, t.fastest_joint);
  }
  CHECK(r.planted_inputs >= least - kExactSliding);  // weights from 0 to 1: among the takes'
  CHECK(r.planted_inputs <= most + kExactSliding);
  // The fastest of the takes mixed (the one dropped came in at weight 0) is what the result's
  // joints are held under: one of the takes'.
  CHECK(std::any_of(m.measures.takes.begin(), m.measures.takes.end(),
                    [&](const TakeMeasures& t) { return t.fastest_joint == r.fastest_inputs; }));
  CHECK(r.fastest_inputs <= fastest);
  REQUIRE(r.fastest_ratio());
  CHECK(*r.fastest_ratio() > 0.5);
  CHECK(*r.fastest_ratio() <= kSpeedLimitOverTakes + 1e-9);
}
