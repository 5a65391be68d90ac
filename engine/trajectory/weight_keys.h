#pragma once
// Style over time: a mix's weights keyed at moments of the output ("a normal walk that
// becomes tired over ten seconds"). Between two keys the weights ease from one set to the next
// (smoothstep: no kink at a key, so no joint changes speed at once); before the first key they
// are the first key's, after the last the last's. A key may fall anywhere, inside a cycle too:
// the ease spans the whole time between keys. The timing follows the weights as they change
// (trajectory/mixed_clock.h mixed_timeline with keys), so the times are seconds of the output itself.
#include <Eigen/Core>
#include <vector>

namespace mostyle {

struct WeightKey {
  double seconds = 0.0;         // of the output, from its first frame
  std::vector<double> weights;  // one per take, as MixParams::weights
};

// Keys in order of time; empty: no keys (the mix's constant weights).
using WeightKeys = std::vector<WeightKey>;

// Throws InputError, in one sentence naming the key (its number and time), on a time that is not
// finite or below 0, times that do not increase, or a key without `takes` weights. The weights'
// own range is checked by MixParams::Validate.
void validate_keys(const WeightKeys& keys, int takes);

// The weights at `seconds` into `out` (resized to the takes; no allocation once it has that size).
// keys: validated, non-empty. O(log keys + takes).
void weights_at(const WeightKeys& keys, double seconds, std::vector<double>& out);

// The same at each of `frames` output frames at `fps`, into out (frames x takes; no allocation
// once it has that size). O(frames x takes + keys).
void weights_over_frames(const WeightKeys& keys, Eigen::Index frames, double fps, Eigen::MatrixXd& out);

}  // namespace mostyle
