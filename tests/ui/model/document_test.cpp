// The editor's document (ui/model/document.h): each take's layer follows its take.
#include "ui/model/document.h"
#include "ui/model/document_fields.h"

#include <catch2/catch.hpp>
#include <iterator>
#include <optional>
#include <utility>
#include <vector>

using namespace mostyle;
using namespace mostyle::ui;

// A layer at weight w, its weights per component `parts` (none: empty).
TakeLayer layer(double w, std::vector<std::optional<double>> parts = {}) { return TakeLayer{w, std::move(parts)}; }

TEST_CASE("reorder_takes: each take keeps its layer (weight and per-part weights) when the content changes") {
  // Takes: normal (content), tired, proud, old. Making "proud" (2) the content moves it first.
  Document d;
  d.files = {"normal.bvh", "tired.bvh", "proud.bvh", "old.bvh"};
  d.layers = {layer(0.63, {1.0, std::nullopt}), layer(0.08, {0.0, std::nullopt}), layer(0.2, {0.0, 0.5}),
              layer(0.09, {0.0, 0.5})};
  DocumentControls& c = d.controls;
  c.neutral = 3;  // old
  c.transfer = true;
  const std::vector<int> order = {2, 0, 1, 3};  // proud, normal, tired, old
  const Document r = reorder_takes(d, order);
  CHECK(layer_weights(r) == std::vector<double>{0.2, 0.63, 0.08, 0.09});
  CHECK(r.files == d.files);  // loaded again in the new order: the engine link sets them
  CHECK(r.layers[0].component_weights == std::vector<std::optional<double>>{0.0, 0.5});
  CHECK(r.layers[1].component_weights == std::vector<std::optional<double>>{1.0, std::nullopt});
  CHECK(r.controls.neutral == 3);
  CHECK(r.controls.transfer);
  // And back: the inverse order gives the document we started from.
  std::vector<int> inverse(order.size());
  for (size_t k = 0; k < order.size(); ++k) inverse[static_cast<size_t>(order[k])] = static_cast<int>(k);
  CHECK(reorder_takes(r, inverse) == d);
  // The neutral moves with its take; layers not sized for these takes are left alone.
  c.neutral = 1;
  set_layer_weights(d, {0.5, 0.5});
  const Document moved = reorder_takes(d, {1, 2, 0, 3});
  CHECK(moved.controls.neutral == 0);
  CHECK(layer_weights(moved) == std::vector<double>{0.5, 0.5});
}

TEST_CASE("pair_alpha: a pair's alpha is its second layer's weight, 0.5 before there is one") {
  Document d;
  CHECK(pair_alpha(d) == 0.5);  // nothing loaded: the default
  set_pair_alpha(d, 0.3);
  CHECK(layer_weights(d) == std::vector<double>{0.7, 0.3});
  CHECK(pair_alpha(d) == 0.3);
  set_pair_alpha(d, 0.0);
  CHECK(layer_weights(d) == std::vector<double>{1.0, 0.0});  // exactly A
  // The layers' weights set keep each layer's weights per component.
  d.layers[1].component_weights = {0.25};
  set_layer_weights(d, {0.2, 0.3, 0.5});
  CHECK(d.layers[1].component_weights == std::vector<std::optional<double>>{0.25});
  CHECK(layer_weights(d) == std::vector<double>{0.2, 0.3, 0.5});
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
      {"mode", [](Document& d) { d.controls.mode = DecompositionMode::kPaper; }, Stale::kDecomposition},
      {"per part", [](Document& d) { d.controls.per_part = true; }, Stale::kMix},
      {"component regions", [](Document& d) { d.controls.component_regions = {BodyRegion::kLeftLeg}; }, Stale::kMix},
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
      {"layers", [](Document& d) { set_pair_alpha(d, 0.7); }, Stale::kMix},
      {"transfer", [](Document& d) { d.controls.transfer = true; }, Stale::kMix},
      {"neutral", [](Document& d) { d.controls.neutral = 2; }, Stale::kMix},
      {"content its own neutral", [](Document& d) { d.controls.content_neutral = true; }, Stale::kMix},
      {"ghosts", [](Document& d) { d.controls.ghosts = false; }, Stale::kView},
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
