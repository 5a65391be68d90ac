#include "ui/model/keyed_weights.h"

#include <algorithm>
#include <cstddef>
#include <utility>

#include "ui/model/weight_keys_edit.h"

namespace mostyle::ui {
namespace {

// Whether the takes are mixed as a transfer: transfer mode, with a style beside the content.
bool is_transfer(const DocumentControls& c, int takes) { return takes >= 2 && c.transfer; }

// w (one per take, two or more) made a transfer's weights in place: the content 1, the neutral
// (take `neutral`, 0 the content itself) minus the styles' sum (transfer_mix_weights).
void make_transfer(std::vector<double>& w, int neutral) {
  const size_t n = static_cast<size_t>(std::clamp(neutral, 0, static_cast<int>(w.size()) - 1));
  double styles = 0.0;
  for (size_t i = 1; i < w.size(); ++i)
    if (i != n) styles += w[i];
  w[0] = 1.0;
  w[n] = (n == 0 ? 1.0 : 0.0) - styles;
}

// The constant controls set from mix weights, as the controls set them without keys: the inverse
// of constant_weights (a transfer's content and neutral weights follow from the styles': only the
// styles' strengths are set, and the content's and the neutral's layers keep what they had for
// when they are styles again).
void set_constant_weights(Document& d, int takes, const std::vector<double>& weights) {
  if (!is_transfer(d.controls, takes)) {
    set_layer_weights(d, weights);
    return;
  }
  const int neutral = transfer_neutral(d.controls, takes);
  if (static_cast<int>(d.layers.size()) != takes) set_layer_weights(d, constant_weights(d, takes));
  for (int i = 1; i < takes; ++i)
    if (i != neutral) d.layers[static_cast<size_t>(i)].weight = weights[static_cast<size_t>(i)];
}

}  // namespace

int transfer_neutral(const DocumentControls& c, int takes) {
  return c.content_neutral || !neutral_take_possible(takes) ? 0 : std::clamp(c.neutral, 1, takes - 1);
}

std::vector<double> transfer_mix_weights(const std::vector<double>& values, int neutral, int takes) {
  std::vector<double> w(values.begin(), values.begin() + std::min<std::ptrdiff_t>(values.size(), takes));
  w.resize(static_cast<size_t>(takes), 0.0);
  make_transfer(w, neutral);
  return w;
}

std::vector<double> constant_weights(const Document& d, int takes) {
  std::vector<double> w = static_cast<int>(d.layers.size()) == takes
                              ? layer_weights(d)
                              : std::vector<double>(static_cast<size_t>(takes), 1.0 / takes);
  if (is_transfer(d.controls, takes)) make_transfer(w, transfer_neutral(d.controls, takes));
  return w;
}

void set_transfer(Document& d, int takes, bool on) {
  if (!on && is_transfer(d.controls, takes)) set_layer_weights(d, constant_weights(d, takes));
  d.controls.transfer = on;
}

void set_mix_keys(const DocumentControls& c, int takes, WeightKeys& out) {
  if (!keys_fit(c.keys, takes)) {
    out.clear();
    return;
  }
  out = c.keys;  // copy-assigned element by element: the vectors out has are reused
  if (is_transfer(c, takes))
    for (WeightKey& key : out) make_transfer(key.weights, transfer_neutral(c, takes));
}

KeyTime key_time(const EditorState& state) {
  const ShownMotion* reference = state.reference_take();
  if (reference == nullptr) return KeyTime{state.playback.time_s, 0.0};
  const double fps = reference->rate();
  return KeyTime{frame_at(*reference, state.playback.time_s) / fps, 0.5 / fps};
}

Keyed keyed_at_playhead(const EditorState& state, int takes) {
  const WeightKeys& keys = state.document.controls.keys;
  if (!keys_fit(keys, takes)) return Keyed::kNo;
  const KeyTime at = key_time(state);
  return key_near(keys, at.seconds, at.tolerance_s) >= 0 ? Keyed::kOnKey : Keyed::kKeyed;
}

std::vector<double> weights_at_playhead(const EditorState& state, int takes) {
  const DocumentControls& c = state.document.controls;
  if (!keys_fit(c.keys, takes)) return constant_weights(state.document, takes);
  std::vector<double> w;
  weights_at(c.keys, key_time(state).seconds, w);
  // The ease is linear in each weight, so easing the styles' and making the transfer's after is
  // the same as easing the transfer's keys (set_mix_keys).
  if (is_transfer(c, takes)) make_transfer(w, transfer_neutral(c, takes));
  return w;
}

void set_weights_at_playhead(EditorState& state, int takes, const std::vector<double>& weights) {
  WeightKeys& keys = state.document.controls.keys;
  if (!keys_fit(keys, takes)) {
    set_constant_weights(state.document, takes, weights);
    return;
  }
  const KeyTime at = key_time(state);
  set_key(keys, at.seconds, at.tolerance_s, weights);
  state.playback.playing = false;  // the playhead stays on the key a drag edits
}

void key_at_playhead(EditorState& state, int takes) {
  std::vector<double> w = weights_at_playhead(state, takes);
  WeightKeys& keys = state.document.controls.keys;
  if (!keys_fit(keys, takes)) keys.clear();
  const KeyTime at = key_time(state);
  set_key(keys, at.seconds, at.tolerance_s, std::move(w));
  command_edited(state);
}

void remove_key(EditorState& state, int takes, int i) {
  WeightKeys& keys = state.document.controls.keys;
  if (i < 0 || i >= static_cast<int>(keys.size())) return;
  if (keys.size() == 1 && keys_fit(keys, takes)) set_constant_weights(state.document, takes, keys.front().weights);
  keys.erase(keys.begin() + i);
  command_edited(state);
}

}  // namespace mostyle::ui
