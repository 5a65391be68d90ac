// The weights the result has at the playhead (ui/model/keyed_weights.h), on an EditorState made by
// hand (a reference take of 301 frames at 30 fps: ten seconds): without keys the controls as they
// were; a key added at the playhead with the weights shown; auto-key editing the key at the
// playhead or adding one; the ease between keys; the last key removed leaving its weights; a
// transfer's keys following the neutral take; keys of another number of takes left out.
#include <memory>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "ui/model/keyed_weights.h"
#include "ui/model/weight_keys_edit.h"

using namespace mostyle;
using namespace mostyle::ui;

namespace {

constexpr double kFps = 30.0;

// `takes` takes loaded (a pair: two), the result ten seconds long, the playhead paused at frame 0.
EditorState loaded(int takes) {
  EditorState state;
  ShownMotion result;
  result.clip = std::make_shared<Clip>();
  result.fps = kFps;
  result.positions = Eigen::MatrixXd::Zero(301, 3);
  state.shown.push_back(result);
  for (int i = 0; i < takes; ++i) state.document.files.push_back("take" + std::to_string(i) + ".bvh");
  state.playback.playing = false;
  return state;
}

// The playhead on `frame`, as the timeline's slider puts it (the middle of the frame).
void go_to(EditorState& state, int frame) { state.playback.time_s = (frame + 0.5) / kFps; }

}  // namespace

TEST_CASE("keyed weights: without keys, the controls show and take the weights as they did") {
  EditorState pair = loaded(2);
  set_pair_alpha(pair.document, 0.3);
  CHECK(weights_at_playhead(pair, 2) == std::vector<double>{0.7, 0.3});
  CHECK(keyed_at_playhead(pair, 2) == Keyed::kNo);
  set_weights_at_playhead(pair, 2, {0.4, 0.6});
  CHECK(pair_alpha(pair.document) == 0.6);
  CHECK(pair.document.controls.keys.empty());

  EditorState palette = loaded(3);
  CHECK(weights_at_playhead(palette, 3) == std::vector<double>(3, 1.0 / 3.0));  // not sized yet: equal
  set_weights_at_playhead(palette, 3, {0.2, 0.3, 0.5});
  CHECK(layer_weights(palette.document) == std::vector<double>{0.2, 0.3, 0.5});
  // A transfer: content 1, each style its strength (its layer's weight), the neutral (take 1)
  // minus their sum.
  DocumentControls& c = palette.document.controls;
  c.transfer = true;
  c.neutral = 1;
  set_layer_weights(palette.document, {9.0, 9.0, 0.8});  // the content's and the neutral's are not used
  CHECK(weights_at_playhead(palette, 3) == std::vector<double>{1.0, -0.8, 0.8});
  set_weights_at_playhead(palette, 3, {1.0, -0.5, 0.5});
  CHECK(layer_weights(palette.document) == std::vector<double>{9.0, 9.0, 0.5});
  CHECK(transfer_mix_weights({0.0, 0.0, 0.5, 1.5}, 2, 4) == std::vector<double>{1.0, 0.0, -1.5, 1.5});
  CHECK(transfer_mix_weights({}, 1, 3) == std::vector<double>{1.0, 0.0, 0.0});  // a value missing counts 0
  // No neutral take: the content is its own neutral, every other take a style; the content 1
  // minus the styles' sum, and the strengths edited are every take's but the content's.
  c.content_neutral = true;
  set_layer_weights(palette.document, {9.0, 0.25, 0.5});
  CHECK(transfer_neutral(c, 3) == 0);
  CHECK(weights_at_playhead(palette, 3) == std::vector<double>{0.25, 0.25, 0.5});
  set_weights_at_playhead(palette, 3, {0.0, 0.4, 0.6});
  CHECK(layer_weights(palette.document) == std::vector<double>{9.0, 0.4, 0.6});
  CHECK(c.neutral == 1);  // kept for when a neutral take is chosen again
  c.content_neutral = false;
  CHECK(transfer_neutral(c, 3) == 1);
  CHECK(weights_at_playhead(palette, 3) == std::vector<double>{1.0, -0.6, 0.6});
  CHECK(transfer_mix_weights({0.0, 0.5, 1.5}, 0, 3) == std::vector<double>{-1.0, 0.5, 1.5});
  // The transfer toggled off: the mix starts from the weights the transfer mixed.
  set_transfer(palette.document, 3, false);
  CHECK(weights_at_playhead(palette, 3) == std::vector<double>{1.0, -0.6, 0.6});
  // And on again: each style's weight its strength, the content's and neutral's made from them.
  set_transfer(palette.document, 3, true);
  CHECK(weights_at_playhead(palette, 3) == std::vector<double>{1.0, -0.6, 0.6});
}

TEST_CASE("keyed weights: a transfer's document before its takes are in has only the weights it holds") {
  // A session in transfer mode whose takes are not loaded (missing, or still loading): no
  // transfer of nothing; layers not one per take, equal weights as the styles' strengths.
  Document d;
  d.controls.transfer = true;
  set_layer_weights(d, {0.0, 1.0, 1.25});
  CHECK(constant_weights(d, 0).empty());
  CHECK(constant_weights(d, 2) == std::vector<double>{0.5, 0.5});  // a pair's: A its own neutral
  CHECK(constant_weights(d, 3) == std::vector<double>{1.0, -1.25, 1.25});  // neutral 1 loses what the style gains
  set_pair_alpha(d, 0.25);
  CHECK(constant_weights(d, 2) == std::vector<double>{0.75, 0.25});
}

TEST_CASE("keyed weights: a normal walk that becomes tired over ten seconds") {
  EditorState state = loaded(2);  // A normal, B tired
  set_pair_alpha(state.document, 0.0);
  // Key alpha 0 at the start: the weights shown, at the start of frame 0.
  const int edits = state.command_edits;
  key_at_playhead(state, 2);
  CHECK(state.command_edits == edits + 1);  // a command: its own undo step
  REQUIRE(state.document.controls.keys.size() == 1);
  CHECK(state.document.controls.keys[0].seconds == 0.0);
  CHECK(state.document.controls.keys[0].weights == std::vector<double>{1.0, 0.0});
  CHECK(keyed_at_playhead(state, 2) == Keyed::kOnKey);
  // Ten seconds in, alpha 1 by moving the slider: auto-key adds a key there, alpha stays.
  go_to(state, 300);
  CHECK(keyed_at_playhead(state, 2) == Keyed::kKeyed);
  CHECK(weights_at_playhead(state, 2) == std::vector<double>{1.0, 0.0});  // held after the last key
  state.playback.playing = true;
  set_weights_at_playhead(state, 2, {0.0, 1.0});
  CHECK_FALSE(state.playback.playing);  // paused: a drag edits this one key
  CHECK(pair_alpha(state.document) == 0.0);
  const WeightKeys& keys = state.document.controls.keys;
  REQUIRE(keys.size() == 2);
  CHECK(keys[1].seconds == Approx(10.0));
  CHECK(keys[1].weights == std::vector<double>{0.0, 1.0});
  // Halfway, the ease is half way (smoothstep(0.5) = 0.5); a quarter in, less than a quarter.
  go_to(state, 150);
  CHECK(weights_at_playhead(state, 2)[1] == Approx(0.5).margin(0.01));
  go_to(state, 75);
  CHECK(weights_at_playhead(state, 2)[1] == Approx(0.15625).margin(0.01));  // 3/16 - 2/64
  // The slider moved on the last frame again: the key there changes, no new key.
  go_to(state, 300);
  set_weights_at_playhead(state, 2, {0.1, 0.9});
  REQUIRE(keys.size() == 2);
  CHECK(keys[1].weights == std::vector<double>{0.1, 0.9});
  // Set key on a key: it takes the weights shown (its own), and no key is added.
  key_at_playhead(state, 2);
  CHECK(keys.size() == 2);
}

TEST_CASE("keyed weights: removing keys, the last one leaves the controls at its weights") {
  EditorState state = loaded(2);
  set_pair_alpha(state.document, 0.2);
  key_at_playhead(state, 2);
  go_to(state, 60);
  set_weights_at_playhead(state, 2, {0.3, 0.7});
  REQUIRE(state.document.controls.keys.size() == 2);
  const int edits = state.command_edits;
  remove_key(state, 2, 0);
  CHECK(state.command_edits == edits + 1);
  CHECK(pair_alpha(state.document) == 0.2);  // keys were left: the controls as they were
  REQUIRE(state.document.controls.keys.size() == 1);
  remove_key(state, 2, 0);
  CHECK(state.document.controls.keys.empty());
  CHECK(pair_alpha(state.document) == 0.7);  // no jump when the last key goes
  remove_key(state, 2, 0);                        // nothing left to remove
  CHECK(state.command_edits == edits + 2);
}

TEST_CASE("keyed weights: the engine's keys, a transfer's made from its styles' weights") {
  DocumentControls c;
  WeightKeys out = {WeightKey{1.0, {0.5, 0.5}}};
  set_mix_keys(c, 2, out);
  CHECK(out.empty());  // no keys: none
  c.keys = {WeightKey{0.0, {1.0, 0.0}}, WeightKey{10.0, {0.0, 1.0}}};
  set_mix_keys(c, 2, out);
  CHECK(same_keys(out, c.keys));  // a pair's as they are
  set_mix_keys(c, 3, out);
  CHECK(out.empty());  // made for two takes: not for three

  // A transfer: each key's content weight 1 and the neutral's minus the styles' sum, made from
  // the styles' weights (their strengths). A key made in a mix (weights summing to 1) reads so; a
  // transfer's own key is the same whichever take is the neutral (its takes but the content sum
  // to 0), so a neutral chosen after the keys plays what the strength sliders show.
  c.transfer = true;
  c.neutral = 1;
  c.keys = {WeightKey{0.0, {0.4, 0.3, 0.2, 0.1}}, WeightKey{4.0, {1.0, -1.5, 1.0, 0.5}}};
  set_mix_keys(c, 4, out);
  REQUIRE(out.size() == 2);
  CHECK(out[0].weights[0] == 1.0);
  CHECK(out[0].weights[1] == Approx(-0.3));
  CHECK(out[0].weights[2] == 0.2);
  CHECK(out[0].weights[3] == 0.1);
  CHECK(out[1].weights == c.keys[1].weights);
  c.neutral = 2;
  set_mix_keys(c, 4, out);
  CHECK(out[0].weights[0] == 1.0);
  CHECK(out[0].weights[1] == 0.3);
  CHECK(out[0].weights[2] == Approx(-0.4));
  CHECK(out[0].weights[3] == 0.1);
  CHECK(out[1].weights == c.keys[1].weights);
  // The content its own neutral: each key's content weight 1 minus every other take's.
  c.content_neutral = true;
  set_mix_keys(c, 4, out);
  CHECK(out[0].weights[0] == Approx(0.4));
  CHECK(out[0].weights[1] == 0.3);
  CHECK(out[1].weights[0] == Approx(1.0 - (-1.5 + 1.0 + 0.5)));
  c.content_neutral = false;
  set_mix_keys(c, 4, out);
  // The weights shown at the playhead are those the engine eases to there (the ease is linear in
  // each weight): halfway between the keys, the mean of the two.
  EditorState state = loaded(4);
  state.document.controls = c;
  go_to(state, 60);  // 2 s
  const std::vector<double> w = weights_at_playhead(state, 4);
  REQUIRE(w.size() == 4);
  for (size_t i = 0; i < 4; ++i) CHECK(w[i] == Approx(0.5 * (out[0].weights[i] + out[1].weights[i])));
}

TEST_CASE("keyed weights: keys made for another number of takes are left out, and a new key replaces them") {
  EditorState state = loaded(3);  // a palette of three, keys of a pair kept from before
  state.document.controls.keys = {WeightKey{0.0, {1.0, 0.0}}, WeightKey{10.0, {0.0, 1.0}}};
  set_layer_weights(state.document, {0.2, 0.3, 0.5});
  CHECK(keyed_at_playhead(state, 3) == Keyed::kNo);
  CHECK(weights_at_playhead(state, 3) == std::vector<double>{0.2, 0.3, 0.5});
  set_weights_at_playhead(state, 3, {0.6, 0.2, 0.2});  // the constant weights, as without keys
  CHECK(layer_weights(state.document) == std::vector<double>{0.6, 0.2, 0.2});
  CHECK(state.document.controls.keys.size() == 2);
  go_to(state, 30);
  key_at_playhead(state, 3);
  REQUIRE(state.document.controls.keys.size() == 1);
  CHECK(state.document.controls.keys[0].seconds == 1.0);
  CHECK(state.document.controls.keys[0].weights == std::vector<double>{0.6, 0.2, 0.2});
}

TEST_CASE("keyed weights: the playhead's key time is the frame shown, with half a frame either side") {
  EditorState state = loaded(2);
  go_to(state, 45);
  const KeyTime at = key_time(state);
  CHECK(at.seconds == 1.5);
  CHECK(at.tolerance_s == Approx(0.5 / kFps));
  state.playback.time_s = 1.5 + 0.9 / kFps;  // while playing: anywhere in the frame
  CHECK(key_time(state).seconds == 1.5);
  EditorState empty;
  empty.playback.time_s = 2.0;
  CHECK(key_time(empty).seconds == 2.0);
  CHECK(key_time(empty).tolerance_s == 0.0);
}
