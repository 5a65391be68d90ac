// Undo and redo over Documents (ui/model/history.h, ui/model/document.h): commit, undo, redo, a new commit
// dropping what could be redone, the cap, and what a Document compares.
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "ui/model/document.h"
#include "ui/model/document_fields.h"
#include "ui/model/history.h"

using namespace mostyle;
using namespace mostyle::ui;

namespace {

Document with_alpha(double alpha) {
  Document d;
  set_pair_alpha(d, alpha);
  d.files = {"/takes/a.bvh", "/takes/b.bvh"};
  return d;
}

}  // namespace

TEST_CASE("history: the first commit is the start, each different one a step") {
  History h;
  CHECK(h.current() == nullptr);
  CHECK_FALSE(h.can_undo());
  CHECK_FALSE(h.can_redo());
  CHECK_FALSE(h.undo().has_value());
  CHECK_FALSE(h.redo().has_value());
  h.commit(with_alpha(0.5));
  REQUIRE(h.current() != nullptr);
  CHECK_FALSE(h.can_undo());  // nothing before the start
  h.commit(with_alpha(0.5));  // the same: no step
  CHECK(h.undo_steps() == 0);
  h.commit(with_alpha(0.6));
  h.commit(with_alpha(0.7));
  CHECK(h.undo_steps() == 2);
  CHECK(pair_alpha(*h.current()) == 0.7);
}

TEST_CASE("history: undo goes back step by step, redo forward again, to each end") {
  History h;
  for (double a : {0.1, 0.2, 0.3, 0.4}) h.commit(with_alpha(a));
  auto d = h.undo();
  REQUIRE(d.has_value());
  CHECK(pair_alpha(*d) == 0.3);
  CHECK(pair_alpha(*h.undo()) == 0.2);
  CHECK(pair_alpha(*h.undo()) == 0.1);
  CHECK_FALSE(h.undo().has_value());  // at the start
  CHECK(pair_alpha(*h.current()) == 0.1);
  CHECK(h.redo_steps() == 3);
  CHECK(pair_alpha(*h.redo()) == 0.2);
  CHECK(pair_alpha(*h.redo()) == 0.3);
  CHECK(pair_alpha(*h.redo()) == 0.4);
  CHECK_FALSE(h.redo().has_value());  // at the end
  CHECK(pair_alpha(*h.current()) == 0.4);
}

TEST_CASE("history: a new commit after undo drops what could be redone") {
  History h;
  for (double a : {0.1, 0.2, 0.3}) h.commit(with_alpha(a));
  h.undo();
  h.undo();
  CHECK(h.can_redo());
  h.commit(with_alpha(0.1));  // the state undone to: no step, redo stays
  CHECK(h.can_redo());
  h.commit(with_alpha(0.9));  // a new change
  CHECK_FALSE(h.can_redo());
  CHECK_FALSE(h.redo().has_value());
  CHECK(pair_alpha(*h.undo()) == 0.1);
  CHECK_FALSE(h.can_undo());
}

TEST_CASE("history: at the cap the oldest steps go") {
  History h(3);
  for (int i = 0; i <= 10; ++i) h.commit(with_alpha(i / 10.0));
  CHECK(h.undo_steps() == 3);
  CHECK(pair_alpha(*h.undo()) == Approx(0.9));
  CHECK(pair_alpha(*h.undo()) == Approx(0.8));
  CHECK(pair_alpha(*h.undo()) == Approx(0.7));
  CHECK_FALSE(h.undo().has_value());
  History defaults;
  for (int i = 0; i < 500; ++i) defaults.commit(with_alpha(i / 1000.0));
  CHECK(defaults.undo_steps() == History::kDefaultSteps);
  h.clear();
  CHECK(h.current() == nullptr);
}

TEST_CASE("document: every edited field counts, the view's own state does not") {
  const Document base = with_alpha(0.5);
  std::vector<Document> changed(12, base);
  changed[0].parameters.components = 4;
  changed[1].parameters.sparsity = 0.3;
  changed[2].controls.mode = DecompositionMode::kPaper;
  changed[3].controls.per_part = true;
  changed[4].controls.foot_lock = false;
  changed[5].controls.align.on = AlignOn::kBody;
  changed[6].controls.align.slope.max_slope = 3;
  set_layer_weights(changed[7], {0.5, 0.25, 0.25});
  changed[8].layers[1].component_weights = {1.0, std::nullopt};
  changed[9].files = {"/takes/a.bvh", "/takes/c.bvh"};
  changed[10].overlay = true;
  changed[11].controls.basic_sparsities = {0.2};
  for (size_t i = 0; i < changed.size(); ++i) {
    INFO(i);
    CHECK(changed[i] != base);
  }
  DocumentControls viewed = base.controls;
  viewed.selected_component = 3;
  viewed.dtw_coordinate = 0;
  CHECK(document_controls(viewed) == base.controls);
  CHECK(stale_after(base, changed[0]) == Stale::kDecomposition);
  CHECK(stale_after(base, changed[2]) == Stale::kDecomposition);
  CHECK(stale_after(base, changed[4]) == Stale::kMix);
  CHECK(same_files({"/takes/x/../a.bvh"}, {"/takes/a.bvh"}));
  CHECK_FALSE(same_files({"/takes/a.bvh"}, {"/takes/b.bvh"}));
  CHECK_FALSE(same_files({"/takes/a.bvh"}, {"/takes/a.bvh", "/takes/a.bvh"}));
}
