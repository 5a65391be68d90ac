// Undo and redo over a loaded session (ui/model/edit_history.h), with the panels drawn as ImGui frames
// with no window: alpha changed in a few steps and a drag, undone back and redone forward; a load
// undone and redone through the worker; a new decomposition resizing the per-component alphas
// makes no step; an opened session whose take is missing keeps the takes and names the file; a key
// set and its mark dragged, undone and redone.
#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <optional>
#include <vector>

#include <catch2/catch.hpp>

#include "tests/test_data.h"
#include "tests/ui/imgui_frame.h"
#include "tests/ui/loaded_takes.h"
#include "ui/model/layer_parts.h"
#include "ui/model/unsaved_question.h"
#include "ui/model/edit_history.h"
#include "ui/model/keyed_weights.h"
#include "ui/model/session_file.h"
#include "ui/model/weight_keys_edit.h"

using namespace mostyle;
using namespace mostyle::ui;
using test::all_panels;
using test::LoadedTakes;

namespace {

// Alpha changes the blend's timing too, so its length: sizes first.
bool same_poses(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && a == b;
}

}  // namespace

TEST_CASE("undo and redo: alpha in a few steps and a drag, back to the start and forward again") {
  LoadedTakes s;
  test::HeadlessImGui imgui;
  auto panels = all_panels(s.engine);
  EditHistory edits;
  // One editor frame: the panels, then the step recorded (held: an item is being dragged).
  auto frame = [&](bool held) {
    imgui.begin_frame();
    s.engine.poll(s.state);
    for (auto& panel : panels) panel->draw(s.state);
    edits.record(s.state, s.engine, held || ImGui::IsAnyItemActive());
    s.engine.sync(s.state, held || ImGui::IsAnyItemActive());
    imgui.end_frame();
  };
  const double start = pair_alpha(s.state.document);
  frame(false);  // the starting state
  for (int i = 0; i < 5; ++i) frame(false);
  CHECK(edits.history().undo_steps() == 0);  // frames with no input make no step
  CHECK_FALSE(edits.can_undo());

  // Three clicks, each a press (held for a frame) and a release that sets alpha.
  const std::vector<double> steps = {0.2, 0.4, 0.6};
  for (double a : steps) {
    frame(true);
    set_pair_alpha(s.state.document, a);
    frame(false);
  }
  // A drag through many values, let go at 0.9: one step.
  for (double a = 0.61; a < 0.9; a += 0.05) {
    set_pair_alpha(s.state.document, a);
    frame(true);
  }
  set_pair_alpha(s.state.document, 0.9);
  frame(false);
  CHECK(edits.history().undo_steps() == 4);
  const Eigen::MatrixXd blend_at_end = s.state.shown[result_index(2)].positions;

  // Back: each undo puts the previous alpha back, and the blend follows in the same frame.
  for (double expected : {0.6, 0.4, 0.2, start}) {
    REQUIRE(edits.undo(s.state, s.engine));
    frame(false);
    CHECK(pair_alpha(s.state.document) == expected);
  }
  CHECK_FALSE(edits.undo(s.state, s.engine));
  CHECK_FALSE(same_poses(s.state.shown[result_index(2)].positions, blend_at_end));
  // Forward again, to the end of the drag.
  for (double expected : {0.2, 0.4, 0.6, 0.9}) {
    REQUIRE(edits.redo(s.state, s.engine));
    frame(false);
    CHECK(pair_alpha(s.state.document) == expected);
  }
  CHECK_FALSE(edits.redo(s.state, s.engine));
  CHECK(same_poses(s.state.shown[result_index(2)].positions, blend_at_end));

  // Undo twice, then a new change: what could be redone is gone.
  edits.undo(s.state, s.engine);
  edits.undo(s.state, s.engine);
  frame(true);
  s.state.document.controls.foot_lock = false;
  frame(false);
  CHECK_FALSE(edits.can_redo());
  REQUIRE(edits.undo(s.state, s.engine));
  CHECK(s.state.document.controls.foot_lock);
  CHECK(pair_alpha(s.state.document) == 0.4);
}

TEST_CASE("undo and redo a load: the takes come back through the worker, and no extra step") {
  LoadedTakes s;
  EditHistory edits;
  const std::string happy = test::asset("motions/cmu142_walk_happy.bvh");
  const std::string marching = test::asset("motions/cmu142_walk_marching.bvh");
  const std::string joy = test::asset("motions/cmu142_walk_joy.bvh");
  edits.record(s.state, s.engine, false);
  s.engine.load(joy, marching);
  CHECK(load_pending(s.engine));
  edits.record(s.state, s.engine, true);  // the Load button, pressed and let go while it loads
  edits.record(s.state, s.engine, false);
  CHECK(edits.history().undo_steps() == 0);  // not while the load is on its way
  s.engine.wait_idle(s.state);
  CHECK_FALSE(load_pending(s.engine));
  edits.record(s.state, s.engine, false);
  CHECK(edits.history().undo_steps() == 1);
  CHECK(edits.history().current()->files == std::vector<std::string>{joy, marching});

  REQUIRE(edits.undo(s.state, s.engine));
  CHECK(s.engine.requested_a() == happy);
  edits.record(s.state, s.engine, false);  // on its way: nothing recorded
  // The worker done with everything (load, decomposition, mix) before the session polls: a
  // frame's record() in that gap still sees the load on its way, and keeps the redo.
  s.engine.sync(s.state);
  for (WorkerStatus w = s.engine.status(); w.stage != WorkerStage::kIdle || w.pending; w = s.engine.status())
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  CHECK(load_pending(s.engine));
  edits.record(s.state, s.engine, false);
  CHECK(edits.can_redo());
  s.engine.wait_idle(s.state);
  CHECK(s.engine.error().empty());
  CHECK(s.engine.snapshot().paths[0] == happy);
  edits.record(s.state, s.engine, false);
  CHECK(edits.history().undo_steps() == 0);
  CHECK(edits.history().redo_steps() == 1);
  REQUIRE(edits.redo(s.state, s.engine));
  s.engine.wait_idle(s.state);
  CHECK(s.engine.snapshot().paths[0] == joy);
  edits.record(s.state, s.engine, false);
  CHECK(edits.history().undo_steps() == 1);
  CHECK_FALSE(edits.can_redo());
}

TEST_CASE("undo and redo k: a new decomposition fitting the layers' weights per component makes no step") {
  LoadedTakes s;
  EditHistory edits;
  set_component_row(s.state.document, *s.engine.snapshot().decomposed, 0, std::vector<double>{0.2, 0.8});
  edits.record(s.state, s.engine, false);
  const int k = s.state.document.parameters.components;
  REQUIRE(s.state.document.layers[1].component_weights.size() == static_cast<size_t>(k));
  s.state.document.parameters.components = k - 2;  // the k slider, let go
  edits.record(s.state, s.engine, true);
  edits.record(s.state, s.engine, false);
  s.engine.wait_idle(s.state);
  CHECK(s.state.document.layers[1].component_weights.size() == static_cast<size_t>(k - 2));
  edits.record(s.state, s.engine, false);
  CHECK(edits.history().undo_steps() == 1);
  REQUIRE(edits.undo(s.state, s.engine));
  CHECK(s.state.document.parameters.components == k);
  s.engine.sync(s.state);  // the engine link, after the panels: k changed, so it asks again
  CHECK(s.engine.decomposition_outdated());
  s.engine.wait_idle(s.state);
  CHECK(s.engine.snapshot().decompose_params.components == k);
  edits.record(s.state, s.engine, false);
  CHECK(edits.can_redo());
}

TEST_CASE("an opened session whose take is missing opens its other takes, restores the rest, names the file") {
  LoadedTakes s;
  Document d = capture_document(s.state);
  set_pair_alpha(d, 0.85);
  d.controls.timing_a = true;
  d.overlay = true;
  const std::string joy = test::asset("motions/cmu142_walk_joy.bvh");
  d.files = {joy, "/nonexistent/folder/walk_gone.bvh"};
  const std::string message = apply_session_document(d, "/sessions/day.mostyle", s.state, s.engine);
  CHECK_THAT(message, Catch::StartsWith("/sessions/day.mostyle: ") && Catch::Contains("/nonexistent/folder/walk_gone.bvh") &&
                          Catch::Contains("other takes") && Catch::Contains("left as it is"));
  CHECK(s.state.document.controls.timing_a);
  CHECK(s.state.document.overlay);
  s.engine.wait_idle(s.state);
  CHECK(capture_document(s.state).files == std::vector<std::string>{joy, joy});  // the take there, with itself
  // None of its takes there: the takes loaded stay, everything else is applied.
  Document gone = d;
  gone.files = {"/nonexistent/a.bvh", "/nonexistent/b.bvh"};
  set_pair_alpha(gone, 0.3);
  CHECK_THAT(apply_session_document(gone, "/sessions/day.mostyle", s.state, s.engine), Catch::Contains("loaded before stay"));
  CHECK_FALSE(load_pending(s.engine));
  CHECK(pair_alpha(s.state.document) == 0.3);
  s.engine.wait_idle(s.state);
  CHECK(capture_document(s.state).files == std::vector<std::string>{joy, joy});
  // Every take there: applied as it is, the takes loaded.
  d.files = {test::asset("motions/cmu142_walk_joy.bvh"), test::asset("motions/cmu142_walk_marching.bvh")};
  CHECK(apply_session_document(d, "/sessions/day.mostyle", s.state, s.engine).empty());
  s.engine.wait_idle(s.state);
  CHECK(capture_document(s.state) == d);
}

TEST_CASE("keep_takes: a session's takes left out take their values with them; the weights sum to 1 again") {
  Document d;
  d.files = {"a.bvh", "b.bvh", "c.bvh", "d.bvh"};
  set_layer_weights(d, {0.4, 0.2, 0.2, 0.2});
  for (size_t i = 0; i < 4; ++i) d.layers[i].component_weights = {0.1 * static_cast<double>(i + 1)};
  const Document kept = keep_takes(d, {0, 1, 3});
  CHECK(kept.files == std::vector<std::string>{"a.bvh", "b.bvh", "d.bvh"});
  const std::vector<double> w = layer_weights(kept);
  CHECK(w[0] == Approx(0.5));
  CHECK(w[1] == Approx(0.25));
  CHECK(w[2] == Approx(0.25));
  CHECK(kept.layers[2].component_weights == std::vector<std::optional<double>>{0.4});
  // A transfer's strengths stay as they are; its neutral (c) gone, the content is its own.
  d.controls.transfer = true;
  d.controls.neutral = 2;
  set_layer_weights(d, {1.0, 0.5, 1.0, 0.25});
  const Document transfer_kept = keep_takes(d, {0, 1, 3});
  CHECK(layer_weights(transfer_kept) == std::vector<double>{1.0, 0.5, 0.25});
  CHECK(transfer_kept.controls.content_neutral);
  const Document neutral_kept = keep_takes(d, {0, 2, 3});
  CHECK_FALSE(neutral_kept.controls.content_neutral);
  CHECK(neutral_kept.controls.neutral == 1);
}

TEST_CASE("undo and redo keys: Set key is a step of its own, a mark's drag one more, and the blend follows") {
  LoadedTakes s;
  EditHistory edits;
  EditorState& state = s.state;
  state.playback.playing = false;
  state.playback.time_s = 0.0;
  edits.record(state, s.engine, false);  // the starting state
  const Eigen::MatrixXd unkeyed = state.shown[result_index(2)].positions;
  // Set key (K: a key pressed, no item held) with alpha 1 in the key: one step, the blend keyed.
  set_pair_alpha(state.document, 1.0);
  key_at_playhead(state, 2);
  set_pair_alpha(state.document, 0.5);  // the constant alpha no longer counts
  edits.record(state, s.engine, false);
  s.engine.sync(state);
  CHECK(edits.history().undo_steps() == 1);
  REQUIRE(state.document.controls.keys.size() == 1);
  const Eigen::MatrixXd keyed = state.shown[result_index(2)].positions;
  // The key's mark dragged over a few frames (held), let go: one step.
  const double fps = state.reference_take()->rate();
  const double length_s = take_length_s(*state.reference_take());
  for (double to : {0.5, 1.0, 1.5}) {
    move_key(state.document.controls.keys, 0, to, 1.0 / fps, length_s);
    edits.record(state, s.engine, true);
  }
  edits.record(state, s.engine, false);
  CHECK(edits.history().undo_steps() == 2);

  REQUIRE(edits.undo(state, s.engine));
  REQUIRE(state.document.controls.keys.size() == 1);
  CHECK(state.document.controls.keys[0].seconds == 0.0);
  REQUIRE(edits.undo(state, s.engine));
  CHECK(state.document.controls.keys.empty());
  s.engine.sync(state);
  CHECK((state.shown[result_index(2)].positions.rows() != keyed.rows() ||
         !state.shown[result_index(2)].positions.isApprox(keyed)));
  REQUIRE(edits.redo(state, s.engine));
  REQUIRE(state.document.controls.keys.size() == 1);
  CHECK(state.document.controls.keys[0].seconds == 0.0);
  s.engine.sync(state);
  CHECK(state.shown[result_index(2)].positions.rows() == keyed.rows());
  CHECK(state.shown[result_index(2)].positions.isApprox(keyed));
  CHECK_FALSE((unkeyed.rows() == keyed.rows() && unkeyed.isApprox(keyed)));
}

TEST_CASE("unsaved edits: none as loaded, one after a change, none once saved or undone back to it") {
  LoadedTakes s;
  EditHistory edits;
  edits.record(s.state, s.engine, false);
  CHECK_FALSE(edits.unsaved());
  set_pair_alpha(s.state.document, 0.8);
  edits.record(s.state, s.engine, true);  // dragged
  edits.record(s.state, s.engine, false);  // let go: a step
  CHECK(edits.unsaved());
  REQUIRE(edits.undo(s.state, s.engine));
  s.engine.sync(s.state);
  edits.record(s.state, s.engine, false);
  CHECK_FALSE(edits.unsaved());  // back as loaded
  REQUIRE(edits.redo(s.state, s.engine));
  edits.record(s.state, s.engine, false);
  CHECK(edits.unsaved());
  edits.mark_saved(capture_document(s.state));
  CHECK_FALSE(edits.unsaved());
  set_pair_alpha(s.state.document, 0.2);
  edits.record(s.state, s.engine, true);
  edits.record(s.state, s.engine, false);
  CHECK(edits.unsaved());
  edits.mark_opened();  // an opened session: what is recorded next is what is saved
  edits.record(s.state, s.engine, false);
  CHECK_FALSE(edits.unsaved());
}

TEST_CASE("closing: at once with nothing unsaved; else asked, and Cancel, Discard or Save answer it") {
  UnsavedQuestion c;
  c.request(false);
  CHECK(c.may_close());
  UnsavedQuestion asked;
  asked.request(true);
  CHECK(asked.asking());
  CHECK_FALSE(asked.may_close());
  asked.answer(UnsavedQuestion::Answer::kCancel);
  CHECK_FALSE(asked.asking());
  CHECK_FALSE(asked.may_close());
  asked.request(true);
  asked.answer(UnsavedQuestion::Answer::kSave);
  CHECK(asked.saving());
  CHECK_FALSE(asked.may_close());
  asked.saved(false);  // not written (or the dialog cancelled): stays open
  CHECK_FALSE(asked.may_close());
  asked.request(true);
  asked.answer(UnsavedQuestion::Answer::kSave);
  asked.saved(true);
  CHECK(asked.may_close());
  UnsavedQuestion discard;
  discard.request(true);
  discard.answer(UnsavedQuestion::Answer::kDiscard);
  CHECK(discard.may_close());
}

TEST_CASE("opening a session over unsaved edits: asked first; the session opens once, after Save or Discard") {
  UnsavedQuestion clean;
  clean.request(false, UnsavedQuestion::Leave::kOpen, "day.mostyle");
  CHECK_FALSE(clean.may_close());  // an open never closes the window
  CHECK(clean.take_open() == std::optional<std::string>("day.mostyle"));
  CHECK_FALSE(clean.take_open());  // once
  UnsavedQuestion asked;
  asked.request(true, UnsavedQuestion::Leave::kOpen, "day.mostyle");
  CHECK(asked.asking());
  CHECK(asked.leave() == UnsavedQuestion::Leave::kOpen);
  CHECK_FALSE(asked.take_open());
  asked.answer(UnsavedQuestion::Answer::kCancel);
  CHECK_FALSE(asked.take_open());
  asked.request(true, UnsavedQuestion::Leave::kOpen, "night.mostyle");
  asked.answer(UnsavedQuestion::Answer::kSave);
  CHECK_FALSE(asked.take_open());  // not before the edits are written
  asked.saved(true);
  CHECK(asked.take_open() == std::optional<std::string>("night.mostyle"));
  asked.request(true, UnsavedQuestion::Leave::kOpen, "day.mostyle");
  asked.answer(UnsavedQuestion::Answer::kDiscard);
  CHECK_FALSE(asked.may_close());
  CHECK(asked.take_open() == std::optional<std::string>("day.mostyle"));
}
