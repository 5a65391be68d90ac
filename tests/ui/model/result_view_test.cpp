// The palette's mix in the editor (ui/model/result_view.h) over a palette of three bundled takes:
// the mix parameters built from the controls carry the keys that fit the takes (a transfer's made
// transfer weights), and a combination the engine refuses (keys with weights per body part) is
// shown as the engine's sentence while the last mix stays.
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "engine/base/error.h"
#include "tests/test_data.h"
#include "tests/ui/loaded_takes.h"
#include "ui/model/document_mix.h"
#include "ui/model/layer_parts.h"
#include "ui/model/weight_keys_edit.h"

using namespace mostyle;
using namespace mostyle::ui;
using test::LoadedTakes;

namespace {

// The bundled pair's session, with a palette of three takes loaded instead.
void load_palette(LoadedTakes& s) {
  s.engine.load_files({test::asset("motions/cmu142_walk_happy.bvh"), test::asset("motions/cmu142_walk_marching.bvh"),
                        test::asset("motions/cmu142_walk_joy.bvh")});
  s.engine.wait_idle(s.state);
}

}  // namespace

TEST_CASE("result view: the mix parameters carry the keys that fit the takes") {
  LoadedTakes s;
  load_palette(s);
  REQUIRE(s.engine.takes() != nullptr);
  const Decomposed& d = *s.engine.snapshot().decomposed;
  Document doc = s.state.document;
  DocumentControls& c = doc.controls;
  set_layer_weights(doc, {0.2, 0.3, 0.5});
  CHECK(mix_params_for(doc, d, 3).keys.empty());
  // Happy becomes joyful over two seconds.
  c.keys = {WeightKey{0.0, {1.0, 0.0, 0.0}}, WeightKey{2.0, {0.0, 0.0, 1.0}}};
  const MixParams keyed = mix_params_for(doc, d, 3);
  CHECK(same_keys(keyed.keys, c.keys));
  CHECK(take_weights(keyed.layers, 3) == layer_weights(doc));  // the constant weights as they were
  // A transfer: the content's and the neutral's weights made from the styles'.
  c.transfer = true;
  c.content_neutral = false;
  c.neutral = 1;
  set_layer_weights(doc, {1.0, 1.0, 0.5});  // the style's strength 0.5
  const MixParams transfer = mix_params_for(doc, d, 3);
  CHECK(take_weights(transfer.layers, 3) == std::vector<double>{1.0, -0.5, 0.5});
  REQUIRE(transfer.keys.size() == 2);
  CHECK(transfer.keys[0].weights == std::vector<double>{1.0, 0.0, 0.0});
  CHECK(transfer.keys[1].weights == std::vector<double>{1.0, -1.0, 1.0});
  // No neutral take: the content is its own, both other takes are styles (content + s (style -
  // content)), the content 1 minus their sum.
  c.content_neutral = true;
  const MixParams own = mix_params_for(doc, d, 3);
  CHECK(take_weights(own.layers, 3) == std::vector<double>{-0.5, 1.0, 0.5});
  CHECK(own.keys[0].weights == std::vector<double>{1.0, 0.0, 0.0});
  CHECK(own.keys[1].weights == std::vector<double>{0.0, 0.0, 1.0});
  c.content_neutral = false;
  // A pair's keys: none for three takes.
  c.keys = {WeightKey{0.0, {1.0, 0.0}}};
  CHECK(mix_params_for(doc, d, 3).keys.empty());
}

TEST_CASE("result view: keys with weights per body part are the engine's sentence, the last mix stays") {
  LoadedTakes s;
  load_palette(s);
  REQUIRE(s.engine.result_view().mix() != nullptr);
  DocumentControls& c = s.state.document.controls;
  c.keys = {WeightKey{0.0, {1.0, 0.0, 0.0}}, WeightKey{2.0, {0.0, 0.0, 1.0}}};
  s.engine.sync(s.state);
  CHECK(s.engine.result_view().error().empty());
  const Eigen::MatrixXd keyed = s.engine.result_view().mix()->motion.world;
  // The legs from the marching take: the engine mixes keys for the whole body only.
  c.per_part = true;
  set_part_row(s.state.document, *s.engine.snapshot().decomposed, BodyPart::kLegs, std::vector<double>{0.0, 1.0, 0.0});
  CHECK_THROWS_AS(mix_params_for(s.state.document, *s.engine.snapshot().decomposed, 3), InputError);
  s.engine.sync(s.state);
  CHECK_THAT(s.engine.result_view().error(), Catch::Contains("keyed in time"));
  CHECK(s.engine.result_view().mix()->motion.world == keyed);
  c.keys.clear();
  s.engine.sync(s.state);
  CHECK(s.engine.result_view().error().empty());
}

TEST_CASE("result view: the weights follow the takes, a take added keeps the others' weights, the new one at 0") {
  using V = std::vector<double>;
  using S = std::vector<std::string>;
  // The same takes keep theirs, for any number of takes.
  CHECK(weights_for_takes({"a", "b"}, {0.7, 0.3}, {"a", "b"}) == V{0.7, 0.3});
  CHECK(weights_for_takes({"a", "b", "c"}, {0.5, 0.2, 0.3}, {"a", "b", "c"}) == V{0.5, 0.2, 0.3});
  CHECK(weights_for_takes({"a", "sub/../b"}, {0.7, 0.3}, {"a", "b"}) == V{0.7, 0.3});  // the same file
  // Takes added at the end: the others keep theirs, the new ones 0.
  CHECK(weights_for_takes({"a", "b"}, {0.7, 0.3}, {"a", "b", "c"}) == V{0.7, 0.3, 0.0});
  CHECK(weights_for_takes({"a", "b", "c"}, {0.5, 0.2, 0.3}, {"a", "b", "c", "d"}) == V{0.5, 0.2, 0.3, 0.0});
  CHECK(weights_for_takes({"a", "a"}, {0.6, 0.4}, {"a", "a", "b"}) == V{0.6, 0.4, 0.0});
  CHECK(weights_for_takes({"a", "b"}, {0.7, 0.3}, {"a", "b", "c", "d"}) == V{0.7, 0.3, 0.0, 0.0});
  // Otherwise equal weights: other takes, fewer, another order, weights that are not one per take
  // of those before, nothing loaded before.
  CHECK(weights_for_takes({"a", "b"}, {0.7, 0.3}, S{"c", "d", "e"}) == V(3, 1.0 / 3));
  CHECK(weights_for_takes({"a", "b"}, {0.7, 0.3}, S{"a", "c"}) == V{0.5, 0.5});  // a new pair: 0.5/0.5
  CHECK(weights_for_takes({"a", "b", "c"}, {0.5, 0.2, 0.3}, {"a", "c"}) == V{0.5, 0.5});
  CHECK(weights_for_takes({"a", "b", "c"}, {0.5, 0.2, 0.3}, {"c", "a", "b"}) == V(3, 1.0 / 3));
  CHECK(weights_for_takes({"a", "b"}, {1.0}, {"a", "b", "c"}) == V(3, 1.0 / 3));
  CHECK(weights_for_takes({"a", "b"}, {}, {"a", "b"}) == V{0.5, 0.5});
  CHECK(weights_for_takes({}, {0.7, 0.3}, {"a", "b"}) == V{0.5, 0.5});
  CHECK(weights_for_takes({"a", "b"}, {0.7, 0.3}, S{}).empty());

  // A pair at 0.7/0.3 (alpha 0.3) given a third take with +.
  LoadedTakes s;
  set_pair_alpha(s.state.document, 0.3);
  std::vector<std::string> takes = s.engine.requested_files();
  REQUIRE(takes.size() == 2);
  takes.push_back(test::asset("motions/cmu142_walk_joy.bvh"));
  s.engine.load_files(takes);
  s.engine.wait_idle(s.state);
  REQUIRE(s.engine.takes() != nullptr);
  const std::vector<double> w = layer_weights(s.state.document);
  REQUIRE(w.size() == 3);
  CHECK(w[0] == Approx(0.7));
  CHECK(w[1] == Approx(0.3));
  CHECK(w[2] == 0.0);
  // And a fourth: the three keep theirs.
  set_layer_weights(s.state.document, {0.5, 0.2, 0.3});
  takes.push_back(test::asset("motions/cmu142_walk_clumsy.bvh"));
  s.engine.load_files(takes);
  s.engine.wait_idle(s.state);
  REQUIRE(s.engine.takes()->size() == 4);
  CHECK(layer_weights(s.state.document) == std::vector<double>{0.5, 0.2, 0.3, 0.0});
}

TEST_CASE("result view: a take added to a transfer keeps every strength and the result; the new one starts at 0") {
  using V = std::vector<double>;
  CHECK(values_for_takes({"a", "b"}, {1.0, 0.5}, {"a", "b", "c"}, 0.0) == V{1.0, 0.5, 0.0});
  CHECK_FALSE(values_for_takes({"a", "b"}, {1.0, 0.5}, {"c", "a", "b"}, 0.0));
  CHECK_FALSE(values_for_takes({"a", "b"}, {}, {"a", "b", "c"}, 0.0));
  // A pair's transfer at strength 0.5 (B's style on A, its alpha), given a third take with +.
  LoadedTakes s;
  s.state.document.controls.transfer = true;
  s.state.document.controls.content_neutral = true;
  set_pair_alpha(s.state.document, 0.5);
  s.engine.sync(s.state);
  s.engine.wait_idle(s.state);
  REQUIRE(s.engine.result_view().mix() != nullptr);
  const Eigen::MatrixXd before = s.engine.result_view().mix()->motion.world;
  std::vector<std::string> takes = s.engine.requested_files();
  takes.push_back(test::asset("motions/cmu142_walk_joy.bvh"));
  s.engine.load_files(takes);
  s.engine.wait_idle(s.state);
  REQUIRE(s.engine.takes() != nullptr);
  const DocumentControls& c = s.state.document.controls;
  CHECK(c.transfer);
  CHECK(c.content_neutral);
  const std::vector<double> strengths = layer_weights(s.state.document);
  REQUIRE(strengths.size() == 3);
  CHECK(strengths[1] == 0.5);
  CHECK(strengths[2] == 0.0);
  REQUIRE(s.engine.result_view().mix() != nullptr);
  // The same result: a take at weight 0 changes no pose (the takes are decomposed again together,
  // and the common timeline is sampled for three, so within a small part of the body's size).
  const Eigen::MatrixXd& after = s.engine.result_view().mix()->motion.world;
  REQUIRE(after.rows() == before.rows());
  Eigen::VectorXd heights(before.cols() / 3);
  for (Eigen::Index j = 0; j < heights.size(); ++j) heights(j) = before.col(3 * j + 1).mean();
  const double size = heights.maxCoeff() - heights.minCoeff();
  const double moved = (after - before).cwiseAbs().maxCoeff();
  const double mean = (after - before).cwiseAbs().mean();
  INFO("largest joint change " << moved / size << " of the body's size, " << mean / size << " on average");
  CHECK(mean < 0.002 * size);
  CHECK(moved < 0.02 * size);
  // A palette's strengths of 0.5 and 0.25, given a fourth take: they stay, the new one at 0.
  set_layer_weights(s.state.document, {1.0, 0.5, 0.25});
  takes.push_back(test::asset("motions/cmu142_walk_clumsy.bvh"));
  s.engine.load_files(takes);
  s.engine.wait_idle(s.state);
  REQUIRE(s.engine.takes()->size() == 4);
  CHECK(layer_weights(s.state.document) == V{1.0, 0.5, 0.25, 0.0});
}

TEST_CASE("result view: new takes' transfer starts on the take named neutral, else on the content as its own") {
  CHECK(named_neutral({"normal.bvh", "bye_active.bvh", "bye_normal.bvh"}) == 2);  // never the content
  CHECK(named_neutral({"a/walk_angry.bvh", "b/Neutral01.fbx"}) == 1);
  CHECK(named_neutral({"walk_angry.bvh", "abnormal_walk.bvh", "neutrality.bvh"}) == -1);
  DocumentControls c;
  size_transfer_controls(c, {}, {"bye_normal.bvh", "bye_active.bvh", "bye_giant.bvh"});
  CHECK(c.content_neutral);  // the content is the normal take: it is its own neutral
  DocumentControls named;
  size_transfer_controls(named, {}, {"bye_active.bvh", "bye_giant.bvh", "bye_normal.bvh"});
  CHECK_FALSE(named.content_neutral);
  CHECK(named.neutral == 2);
}

TEST_CASE("result view: weights set for the takes asked for stay theirs; other takes in their place get equal weights") {
  const std::string happy = test::asset("motions/cmu142_walk_happy.bvh"),
                    marching = test::asset("motions/cmu142_walk_marching.bvh"),
                    joy = test::asset("motions/cmu142_walk_joy.bvh"), clumsy = test::asset("motions/cmu142_walk_clumsy.bvh");
  LoadedTakes s;
  REQUIRE(layer_weights(s.state.document) == std::vector<double>{0.5, 0.5});  // a pair's default, sized
  // Undo, a session or the command line: the weights are the new takes' already.
  set_layer_weights(s.state.document, {0.2, 0.5, 0.3});
  s.engine.load_files({happy, marching, joy}, WeightsOf::kNewTakes);
  s.engine.wait_idle(s.state);
  REQUIRE(s.engine.takes() != nullptr);
  CHECK(layer_weights(s.state.document) == std::vector<double>{0.2, 0.5, 0.3});
  // Another order (a new content): reordered with them, each take keeps its weight.
  s.state.document = reorder_takes(s.state.document, {2, 0, 1});
  s.engine.load_files({joy, happy, marching}, WeightsOf::kNewTakes);
  s.engine.wait_idle(s.state);
  CHECK(s.state.document.files.back() == marching);
  CHECK(layer_weights(s.state.document) == std::vector<double>{0.3, 0.2, 0.5});
  // A take replaced by another: as many takes, not the same ones, equal weights.
  s.engine.load_files({joy, happy, clumsy});
  s.engine.wait_idle(s.state);
  CHECK(layer_weights(s.state.document) == std::vector<double>(3, 1.0 / 3));
  // A take taken out: a pair again, at 0.5/0.5; another pair the same.
  set_layer_weights(s.state.document, {0.6, 0.3, 0.1});
  s.engine.load_files({joy, happy});
  s.engine.wait_idle(s.state);
  CHECK(layer_weights(s.state.document) == std::vector<double>{0.5, 0.5});
  set_pair_alpha(s.state.document, 0.9);
  s.engine.load_files({joy, clumsy});
  s.engine.wait_idle(s.state);
  CHECK(pair_alpha(s.state.document) == 0.5);
  // The same takes aligned again: their weights stay.
  set_pair_alpha(s.state.document, 0.8);
  s.state.document.controls.align.on = AlignOn::kHands;
  s.engine.wait_idle(s.state);
  CHECK(pair_alpha(s.state.document) == 0.8);
}

TEST_CASE("result view: a held slider mixes a preview, let go it is finished into the whole mix") {
  LoadedTakes s;
  REQUIRE(s.engine.result() != nullptr);
  CHECK_FALSE(s.engine.result_view().previewing());
  set_pair_alpha(s.state.document, 0.3);
  s.engine.sync(s.state, /*item_held=*/true);  // the alpha slider dragged
  CHECK(s.engine.result_view().previewing());
  CHECK(s.engine.result()->motion.foot_sliding_cleaned == 0.0);  // no foot lock, no measures yet
  s.engine.sync(s.state, /*item_held=*/true);  // still held, nothing new: still the preview
  CHECK(s.engine.result_view().previewing());
  s.engine.sync(s.state, /*item_held=*/false);  // let go
  CHECK_FALSE(s.engine.result_view().previewing());
  // The same as one whole mix of the document.
  const PreparedTakes& p = *s.engine.takes();
  const Decomposed& d = *s.engine.snapshot().decomposed;
  MixScratch scratch;
  MixResult whole;
  mix_palette(p, d, mix_params_for(s.state.document, d, p.size()), scratch, whole);
  CHECK(s.engine.result()->motion.world == whole.motion.world);
  CHECK(s.engine.result()->motion.contacts == whole.motion.contacts);
  CHECK(s.engine.result()->motion.foot_sliding_cleaned == whole.motion.foot_sliding_cleaned);
  CHECK(s.state.shown.back().positions.rows() == whole.motion.world.rows());
}

TEST_CASE("result view: a pair at alpha a is the engine's mix of its two layers, 1 - a and a, at any alpha the mix allows") {
  LoadedTakes s;
  const PreparedTakes& p = *s.engine.takes();
  const Decomposed& d = *s.engine.snapshot().decomposed;
  for (double a : {0.0, 0.3, 1.0, -0.5, 1.5}) {
    INFO("alpha " << a);
    set_pair_alpha(s.state.document, a);
    s.engine.sync(s.state);
    CHECK(s.engine.result_error().empty());
    // What the editor mixed for a pair before its weights were layers: weights (1 - a, a), the
    // document's options at their defaults.
    MixParams blend;
    blend.layers = take_layers({1.0 - a, a});
    MixScratch scratch;
    MixResult out;
    mix_palette(p, d, blend, scratch, out);
    CHECK(s.engine.result()->motion.world == out.motion.world);
  }
  // Beyond the mix's range: the engine's sentence, the last result stays.
  const Eigen::MatrixXd last = s.engine.result()->motion.world;
  set_pair_alpha(s.state.document, 1.6);
  s.engine.sync(s.state);
  CHECK_THAT(s.engine.result_error(), Catch::Contains("expected weights from -0.50 to 1.50"));
  CHECK(s.engine.result()->motion.world == last);
}
