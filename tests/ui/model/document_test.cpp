// The editor's document (ui/model/document.h): a palette's per-take values follow their takes.
#include "ui/model/document.h"
#include "ui/model/document_fields.h"

#include <catch2/catch.hpp>
#include <iterator>

using namespace mostyle;
using namespace mostyle::ui;

TEST_CASE("reorder_takes: each take keeps its weight, per-part weights and strength when the content changes") {
  // Takes: normal (content), tired, proud, old. Making "proud" (2) the content moves it first.
  Document d;
  d.files = {"normal.bvh", "tired.bvh", "proud.bvh", "old.bvh"};
  d.weights = {0.63, 0.08, 0.2, 0.09};
  PaletteControls& c = d.controls.palette;
  c.part_weights = {{1, 0, 0, 0}, {}, {0, 0, 0.5, 0.5}};
  c.strengths = {0.0, 1.5, -1.0, 0.7};
  c.neutral = 3;  // old
  c.transfer = true;
  const std::vector<int> order = {2, 0, 1, 3};  // proud, normal, tired, old
  const Document r = reorder_takes(d, order);
  CHECK(r.weights == std::vector<double>{0.2, 0.63, 0.08, 0.09});
  CHECK(r.files == d.files);  // loaded again in the new order: the engine link sets them
  const PaletteControls& rc = r.controls.palette;
  CHECK(rc.part_weights[0] == std::vector<double>{0, 1, 0, 0});
  CHECK(rc.part_weights[1].empty());  // "the weights": nothing to reorder
  CHECK(rc.part_weights[2] == std::vector<double>{0.5, 0, 0, 0.5});
  CHECK(rc.strengths == std::vector<double>{-1.0, 0.0, 1.5, 0.7});
  CHECK(rc.neutral == 3);
  CHECK(rc.transfer);
  // And back: the inverse order gives the document we started from.
  std::vector<int> inverse(order.size());
  for (size_t k = 0; k < order.size(); ++k) inverse[static_cast<size_t>(order[k])] = static_cast<int>(k);
  CHECK(reorder_takes(r, inverse) == d);
  // The neutral moves with its take; values not sized for these takes are left alone.
  c.neutral = 1;
  d.weights = {0.5, 0.5};
  const Document moved = reorder_takes(d, {1, 2, 0, 3});
  CHECK(moved.controls.palette.neutral == 0);
  CHECK(moved.weights == std::vector<double>{0.5, 0.5});
}

TEST_CASE("pair_alpha: a pair's alpha is its second weight, 0.5 while the weights are not a pair's") {
  Document d;
  CHECK(pair_alpha(d) == 0.5);  // nothing loaded: the default
  set_pair_alpha(d, 0.3);
  CHECK(d.weights == std::vector<double>{0.7, 0.3});
  CHECK(pair_alpha(d) == 0.3);
  set_pair_alpha(d, 0.0);
  CHECK(d.weights == std::vector<double>{1.0, 0.0});  // exactly A
  d.weights = {0.2, 0.3, 0.5};
  CHECK(pair_alpha(d) == 0.5);  // a palette's weights: no alpha
}

TEST_CASE("document fields: each one, changed alone, differs and makes stale what it should", "[document]") {
  struct Change {
    const char* what;
    void (*apply)(Document&);
    Stale stale;
  };
  // By hand, from what each control does in the editor.
  const Change changes[] = {
      {"k", [](Document& d) { d.parameters.components = 4; }, Stale::kDecomposition},
      {"sparsity", [](Document& d) { d.parameters.sparsity = 0.3; }, Stale::kDecomposition},
      {"mode", [](Document& d) { d.controls.mode = BlendMode::kPaper; }, Stale::kDecomposition},
      {"per component", [](Document& d) { d.controls.per_component = true; }, Stale::kMix},
      {"component alphas", [](Document& d) { d.controls.component_alpha = {0.1, 0.9}; }, Stale::kMix},
      {"basic motions", [](Document& d) { d.controls.basic_motions = 2; }, Stale::kDecomposition},
      {"basic sparsities", [](Document& d) { d.controls.basic_sparsities = {0.2}; }, Stale::kDecomposition},
      {"swap level", [](Document& d) { d.controls.swap_level = 1; }, Stale::kMix},
      {"foot lock", [](Document& d) { d.controls.foot_lock = false; }, Stale::kMix},
      {"align on", [](Document& d) { d.controls.align.on = AlignOn::kHands; }, Stale::kAlignment},
      {"time warp", [](Document& d) { d.controls.align.method = DtwMethod::kPaper; }, Stale::kAlignment},
      {"A's timing", [](Document& d) { d.controls.timing_a = true; }, Stale::kMix},
      {"loop", [](Document& d) { d.controls.loop = true; }, Stale::kMix},
      {"components only", [](Document& d) { d.controls.residual = false; }, Stale::kMix},
      {"keys", [](Document& d) { d.controls.keys = {WeightKey{1.0, {0.5, 0.5}}}; }, Stale::kMix},
      {"picked component", [](Document& d) { d.controls.selected_component = 3; }, Stale::kView},
      {"DTW coordinate", [](Document& d) { d.controls.dtw_coordinate = 0; }, Stale::kView},
      {"weights", [](Document& d) { set_pair_alpha(d, 0.7); }, Stale::kMix},
      {"per part", [](Document& d) { d.controls.palette.per_part = true; }, Stale::kMix},
      {"part weights", [](Document& d) { d.controls.palette.part_weights = {{0.5, 0.5}}; }, Stale::kMix},
      {"transfer", [](Document& d) { d.controls.palette.transfer = true; }, Stale::kMix},
      {"content", [](Document& d) { d.controls.palette.content = 2; }, Stale::kMix},
      {"neutral", [](Document& d) { d.controls.palette.neutral = 2; }, Stale::kMix},
      {"content its own neutral", [](Document& d) { d.controls.palette.content_neutral = true; }, Stale::kMix},
      {"strengths", [](Document& d) { d.controls.palette.strengths = {1.0, 0.5}; }, Stale::kMix},
      {"ghosts", [](Document& d) { d.controls.palette.ghosts = true; }, Stale::kView},
      {"files", [](Document& d) { d.files = {"a.bvh", "b.bvh"}; }, Stale::kTakes},
      {"overlay", [](Document& d) { d.overlay = true; }, Stale::kView},
  };
  const Document base;
  for (const Change& c : changes) {
    INFO(c.what);
    Document changed = base;
    c.apply(changed);
    CHECK_FALSE(changed == base);
    CHECK(stale_after(base, changed) == c.stale);
    CHECK(stale_after(changed, base) == c.stale);
  }
  // Every field the list describes is one of these changes (a field added to the list without a
  // change here, or the other way round, is caught); align on and time warp are one field.
  int fields = 0;
  document_fields(base, base, [&](const Field&, const auto&, const auto&) { ++fields; });
  CHECK(fields == static_cast<int>(std::size(changes)) - 1);
  // Keys compare key by key: a key moved in time or one weight changed is a change of the mix.
  Document keyed = base;
  keyed.controls.keys = {WeightKey{1.0, {0.5, 0.5}}, WeightKey{4.0, {0.0, 1.0}}};
  const Document same = keyed;
  CHECK(same == keyed);
  Document moved = keyed;
  moved.controls.keys[1].seconds = 4.5;
  CHECK(stale_after(keyed, moved) == Stale::kMix);
  Document reweighted = keyed;
  reweighted.controls.keys[0].weights[1] = 0.6;
  CHECK(stale_after(keyed, reweighted) == Stale::kMix);
  CHECK(differs_at(keyed, reweighted, Stale::kMix));
  // Several changes: the most they make stale.
  Document several = base;
  set_pair_alpha(several, 0.2);
  several.overlay = true;
  CHECK(stale_after(base, several) == Stale::kMix);
  several.controls.align.on = AlignOn::kBody;
  several.parameters.components = 5;
  CHECK(stale_after(base, several) == Stale::kAlignment);
  CHECK(stale_after(base, base) == Stale::kNothing);
}
