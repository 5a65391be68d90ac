#pragma once
// Style over time in the editor: a list of weight keys (engine/trajectory/weight_keys.h) as
// the timeline edits it: a key set at a moment (the key already there replaced), moved in time
// between its neighbours, the list compared and put in another order of takes. Pure functions on
// plain data: no ImGui, no engine work. Times are seconds of the result from its first frame (the
// playhead's clock: ui/model/keyed_weights.h key_time); a key's weights are one per take.
#include <vector>

#include "engine/trajectory/weight_keys.h"

namespace mostyle::ui {

// Key by key, the same times and weights (the engine's WeightKey has no ==). O(keys x takes).
bool same_keys(const WeightKeys& x, const WeightKeys& y);

// Whether the keys apply to `takes` takes: at least one key, each with `takes` weights. Keys made
// for another number of takes (another palette loaded since) stay in the document, neither drawn
// nor mixed, until they fit again or a new key replaces them. O(keys).
bool keys_fit(const WeightKeys& keys, int takes);

// Index of the key nearest `seconds` within tolerance_s (ends included); -1 when there is none.
// keys: in order of time. O(log keys).
int key_near(const WeightKeys& keys, double seconds, double tolerance_s);

// Sets the key within tolerance_s of `seconds` to `weights` (its time kept), or adds a key at
// `seconds` in its place in time. Returns the key's index. keys: in order, and stay so. O(keys).
int set_key(WeightKeys& keys, double seconds, double tolerance_s, std::vector<double> weights);

// Moves key i towards `seconds`, kept at least gap_s (> 0) after the key before it and before the
// key after it, and within [0, length_s], so the keys keep their order. Returns the key's time
// (unchanged when its neighbours leave it no room). i: a key of `keys`. O(1).
double move_key(WeightKeys& keys, int i, double seconds, double gap_s, double length_s);

// The keys with each key's weights in another order of takes, as reorder_takes
// (ui/model/document.h) puts a palette's per-take values: weight k of a key is weight order[k] of
// the one given. A key with another number of weights is left as it is. O(keys x takes).
WeightKeys reorder_keys(const WeightKeys& keys, const std::vector<int>& order);

}  // namespace mostyle::ui
