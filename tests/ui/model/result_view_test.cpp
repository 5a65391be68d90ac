// The palette's mix in the editor (ui/model/result_view.h) over a palette of three bundled takes:
// the mix parameters built from the controls carry the keys that fit the takes (a transfer's made
// transfer weights), and a combination the engine refuses (keys with weights per body part) is
// shown as the engine's sentence while the last mix stays.
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "engine/base/error.h"
#include "tests/test_data.h"
#include "tests/ui/loaded_session.h"
#include "ui/model/document_mix.h"
#include "ui/model/weight_keys_edit.h"

using namespace mostyle;
using namespace mostyle::ui;
using test::LoadedSession;

namespace {

// The bundled pair's session, with a palette of three takes loaded instead.
void load_palette(LoadedSession& s) {
  s.session.load_files({test::asset("motions/cmu142_walk_happy.bvh"), test::asset("motions/cmu142_walk_marching.bvh"),
                        test::asset("motions/cmu142_walk_joy.bvh")});
  s.session.wait_idle(s.state);
}

}  // namespace

TEST_CASE("result view: the mix parameters carry the keys that fit the takes") {
  LoadedSession s;
  load_palette(s);
  REQUIRE(s.session.palette() != nullptr);
  const Decomposed& d = *s.session.snapshot().decomposed;
  Document doc = s.state.document;
  DocumentControls& c = doc.controls;
  c.palette.weights = {0.2, 0.3, 0.5};
  CHECK(mix_params_for(doc, d, 3).keys.empty());
  // Happy becomes joyful over two seconds.
  c.keys = {WeightKey{0.0, {1.0, 0.0, 0.0}}, WeightKey{2.0, {0.0, 0.0, 1.0}}};
  const MixParams keyed = mix_params_for(doc, d, 3);
  CHECK(same_keys(keyed.keys, c.keys));
  CHECK(keyed.weights == c.palette.weights);  // the constant weights as they were
  // A transfer: the content's and the neutral's weights made from the styles'.
  c.palette.transfer = true;
  c.palette.neutral = 1;
  c.palette.strengths = {1.0, 1.0, 0.5};
  const MixParams transfer = mix_params_for(doc, d, 3);
  CHECK(transfer.weights == std::vector<double>{1.0, -0.5, 0.5});
  REQUIRE(transfer.keys.size() == 2);
  CHECK(transfer.keys[0].weights == std::vector<double>{1.0, 0.0, 0.0});
  CHECK(transfer.keys[1].weights == std::vector<double>{1.0, -1.0, 1.0});
  // No neutral take: the content is its own, both other takes are styles (content + s (style -
  // content)), the content 1 minus their sum.
  c.palette.content_neutral = true;
  const MixParams own = mix_params_for(doc, d, 3);
  CHECK(own.weights == std::vector<double>{-0.5, 1.0, 0.5});
  CHECK(own.keys[0].weights == std::vector<double>{1.0, 0.0, 0.0});
  CHECK(own.keys[1].weights == std::vector<double>{0.0, 0.0, 1.0});
  c.palette.content_neutral = false;
  // A pair's keys: none for three takes.
  c.keys = {WeightKey{0.0, {1.0, 0.0}}};
  CHECK(mix_params_for(doc, d, 3).keys.empty());
}

TEST_CASE("result view: keys with weights per body part are the engine's sentence, the last mix stays") {
  LoadedSession s;
  load_palette(s);
  REQUIRE(s.session.result_view().mix() != nullptr);
  DocumentControls& c = s.state.document.controls;
  c.keys = {WeightKey{0.0, {1.0, 0.0, 0.0}}, WeightKey{2.0, {0.0, 0.0, 1.0}}};
  s.session.sync(s.state);
  CHECK(s.session.result_view().error().empty());
  const Eigen::MatrixXd keyed = s.session.result_view().mix()->motion.world;
  // The legs from the marching take: the engine mixes keys for the whole body only.
  c.palette.per_part = true;
  c.palette.part_weights = {{0.0, 1.0, 0.0}, {}, {}};
  CHECK_THROWS_AS(mix_params_for(s.state.document, *s.session.snapshot().decomposed, 3), InputError);
  s.session.sync(s.state);
  CHECK_THAT(s.session.result_view().error(), Catch::Contains("keyed in time"));
  CHECK(s.session.result_view().mix()->motion.world == keyed);
  c.keys.clear();
  s.session.sync(s.state);
  CHECK(s.session.result_view().error().empty());
}

TEST_CASE("result view: a take added keeps the others' weights, the new one at 0") {
  using V = std::vector<double>;
  using S = std::vector<std::string>;
  CHECK(weights_with_added_takes({"a", "b"}, {0.7, 0.3}, {"a", "b", "c"}) == V{0.7, 0.3, 0.0});
  CHECK(weights_with_added_takes({"a", "b", "c"}, {0.5, 0.2, 0.3}, {"a", "b", "c", "d"}) == V{0.5, 0.2, 0.3, 0.0});
  CHECK(weights_with_added_takes({"a", "a"}, {0.6, 0.4}, {"a", "a", "b"}) == V{0.6, 0.4, 0.0});
  CHECK(weights_with_added_takes({"a", "b"}, {0.7, 0.3}, S{"c", "d", "e"}).empty());      // all new: equal weights
  CHECK(weights_with_added_takes({"a", "b", "c"}, {0.5, 0.2, 0.3}, {"a", "c"}).empty());  // fewer
  CHECK(weights_with_added_takes({"a", "b"}, {1.0}, {"a", "b", "c"}).empty());            // weights of other takes

  // A pair at 0.7/0.3 (alpha 0.3) given a third take with +.
  LoadedSession s;
  s.state.document.parameters.alpha = 0.3;
  std::vector<std::string> takes = s.session.requested_files();
  REQUIRE(takes.size() == 2);
  takes.push_back(test::asset("motions/cmu142_walk_joy.bvh"));
  s.session.load_files(takes);
  s.session.wait_idle(s.state);
  REQUIRE(s.session.palette() != nullptr);
  const std::vector<double>& w = s.state.document.controls.palette.weights;
  REQUIRE(w.size() == 3);
  CHECK(w[0] == Approx(0.7));
  CHECK(w[1] == Approx(0.3));
  CHECK(w[2] == 0.0);
  // And a fourth: the three keep theirs.
  s.state.document.controls.palette.weights = {0.5, 0.2, 0.3};
  takes.push_back(test::asset("motions/cmu142_walk_clumsy.bvh"));
  s.session.load_files(takes);
  s.session.wait_idle(s.state);
  REQUIRE(s.session.palette()->size() == 4);
  CHECK(s.state.document.controls.palette.weights == std::vector<double>{0.5, 0.2, 0.3, 0.0});
}

TEST_CASE("result view: a held slider mixes a preview, let go it is finished into the whole mix") {
  LoadedSession s;
  REQUIRE(s.session.result() != nullptr);
  CHECK_FALSE(s.session.result_view().previewing());
  s.state.document.parameters.alpha = 0.3;
  s.session.sync(s.state, /*item_held=*/true);  // the alpha slider dragged
  CHECK(s.session.result_view().previewing());
  CHECK(s.session.result()->motion.foot_sliding_cleaned == 0.0);  // no foot lock, no measures yet
  s.session.sync(s.state, /*item_held=*/true);  // still held, nothing new: still the preview
  CHECK(s.session.result_view().previewing());
  s.session.sync(s.state, /*item_held=*/false);  // let go
  CHECK_FALSE(s.session.result_view().previewing());
  // The same as one whole mix of the document.
  const PreparedTakes& p = *s.session.takes();
  const Decomposed& d = *s.session.snapshot().decomposed;
  MixScratch scratch;
  MixResult whole;
  mix_palette(p, d, mix_params_for(s.state.document, d, p.size()), scratch, whole);
  CHECK(s.session.result()->motion.world == whole.motion.world);
  CHECK(s.session.result()->motion.contacts == whole.motion.contacts);
  CHECK(s.session.result()->motion.foot_sliding_cleaned == whole.motion.foot_sliding_cleaned);
  CHECK(s.state.takes.back().positions.rows() == whole.motion.world.rows());
}
