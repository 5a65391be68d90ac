#pragma once
// Style over time in the editor: the weights the result has at a moment, from the
// document's constant weights (Document::weights, a transfer's strengths) or from its
// keys (DocumentControls::keys), and the edits the weight controls, the timeline's Key button and
// its marks make at the playhead. Plain data: no ImGui; tests drive it with an EditorState made
// by hand.
//
// One representation, the layers' (Document::layers): a key holds one weight per take, the
// weights the engine's layers give each take (mix_layers.h take_weights): a pair's (1 - alpha,
// alpha), a mix's weights, a transfer's transfer weights (the content 1, each style its strength,
// the neutral minus their sum; with the content its own neutral, the content 1 minus their sum).
// In a transfer the content's and neutral's weights are always made again from the styles'
// (transfer_mix_weights), so a key follows a neutral or content chosen after it as the layers'
// strengths do, and what the strength sliders show at the playhead is what plays.
//
// Times: seconds of the result from its first frame. The playhead (Playback::time_s) runs on the
// reference take, and every take the editor shows is on the result's timeline (a pair's A and B
// where the blend is in each, a palette's mix first), so the playhead's frame is the result's
// frame, at the result's rate: key_time is that frame's time.
#include <vector>

#include "engine/trajectory/weight_keys.h"
#include "ui/model/document.h"
#include "ui/model/editor_state.h"

namespace mostyle::ui {

// Whether a transfer of `takes` takes can have a neutral take: one needs a style beside it and the
// content, so a pair's transfer has none (B's style on A, A its own neutral).
inline bool neutral_take_possible(int takes) { return takes >= 3; }

// A transfer's neutral take among `takes` (takes >= 2): 0 when the content (take 0) is its own
// neutral (DocumentControls::content_neutral, or no neutral take possible), else its neutral
// clamped to 1 .. takes - 1.
int transfer_neutral(const DocumentControls& c, int takes);

// A transfer's mix weights from per-take values (the layers' weights, or a key's weights):
// the content (take 0: the takes are prepared with it first) 1, each style its value, the
// neutral (transfer_neutral: clamped to 0 .. takes - 1; 0, the content itself) minus the styles'
// sum; every take but the content and the neutral is a style; a value missing counts 0. takes >= 2.
std::vector<double> transfer_mix_weights(const std::vector<double>& values, int neutral, int takes);

// The document's mix weights with nothing keyed, one per take: the layers' weights (equal ones
// while they are not one per take, so a pair's default is 0.5/0.5), in transfer mode
// transfer_mix_weights of them (the styles' are their strengths).
std::vector<double> constant_weights(const Document& d, int takes);

// Transfer mode on or off. Off, the layers take the transfer's weights (constant_weights): the
// mix starts from what the transfer showed (a pair's alpha stays its alpha). On, each style's
// weight is its strength.
void set_transfer(Document& d, int takes, bool on);

// The keys as the engine takes them (MixParams::keys) into `out`: none unless they fit the takes
// (keys_fit); in a transfer each key's content and neutral weights made from
// its styles' (transfer_mix_weights). No allocation once `out` has the keys' sizes (a slider's
// every frame). O(keys x takes).
void set_mix_keys(const DocumentControls& c, int takes, WeightKeys& out);

// The playhead as keys see it: the time of the frame shown (seconds of the result) and half a
// frame, within which a key is the one at the playhead. Without a take: the playhead's own time
// and no tolerance.
struct KeyTime {
  double seconds = 0.0;
  double tolerance_s = 0.0;
};
KeyTime key_time(const EditorState& state);

// What the weight controls show of the keys: none that fit the takes; keyed, with no key at the
// playhead (the value eased between keys, or held before the first and after the last); or a key
// at the playhead.
enum class Keyed { kNo, kKeyed, kOnKey };
Keyed keyed_at_playhead(const EditorState& state, int takes);

// The mix weights the result has at the playhead: keyed (weights_at of the keys as set_mix_keys
// gives them) when the keys fit the takes, else constant_weights. What the weight controls show.
// O(log keys + takes).
std::vector<double> weights_at_playhead(const EditorState& state, int takes);

// Auto-key, the weight controls' edit: `weights` (mix weights, one per take) at the playhead.
// With keys that fit the takes, the key at the playhead takes them, or a new key there, and the
// playback pauses (a drag edits one key); without keys, the constant weights take them
// (the layers' weights; in a transfer the styles' strengths), as those controls set them
// themselves.
void set_weights_at_playhead(EditorState& state, int takes, const std::vector<double>& weights);

// The timeline's Key button and K: a key at the playhead with the weights shown there, the one
// already there replaced; keys that do not fit the takes are replaced by it (undo brings them
// back). A command edit (command_edited): one undo step.
void key_at_playhead(EditorState& state, int takes);

// Removes key i (a key of the document's); the last one leaves the constant controls at its
// weights, so the result does not jump. A command edit: one undo step.
void remove_key(EditorState& state, int takes, int i);

}  // namespace mostyle::ui
