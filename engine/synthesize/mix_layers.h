#pragma once
// A mix as layers, the model of ozz-animation's BlendingJob: normal layers, each a take with a
// weight for the whole body and, when asked, a weight per component (ozz's per-joint weights; body
// parts give them, mix_palette.h part_weights), the normal layers' weights summing to 1; and
// additive layers on top, each adding weight x (take - from), a take's change from another. A
// blend of two takes at alpha is two normal layers, 1 - alpha and alpha; a transfer,
// content + s (style - neutral), is the content's normal layer at 1 and one additive layer of
// weight s per style, from the neutral take (or from the content itself when it is its own
// neutral). What the mix weighs each take's poses, timing, root and feet with is the sum of the
// layers' weights on it (take_weights): one weight per take, or per component and take.
#include <Eigen/Core>
#include <vector>

namespace mostyle {

struct MixLayer {
  int take = 0;         // which take (an index into the prepared takes)
  double weight = 0.0;  // for the whole body
  // One per component (k): the layer's weight there; empty: `weight` for every component.
  std::vector<double> component_weights;
};

struct AdditiveLayer {
  int take = 0;         // the take whose change is added (a style)
  int from = 0;         // the take the change is measured from (a neutral, or the content itself)
  double weight = 0.0;  // the strength s: adds s (take - from)
  std::vector<double> component_weights;  // one strength per component; empty: `weight` everywhere
};

struct MixLayers {
  std::vector<MixLayer> layers;           // their weights sum to 1
  std::vector<AdditiveLayer> additive;    // each adds as much to its take as it takes from `from`
  bool per_component() const;             // some layer has weights per component
};

// One normal layer per take: take i at weights[i]. With `component_weights` (k x N, empty:
// none), take i's layer has column i as its weights per component.
MixLayers take_layers(const std::vector<double>& weights, const Eigen::MatrixXd& component_weights = Eigen::MatrixXd());

// What a transfer's change is measured from: a neutral take (the action without the style), or
// the content itself (no neutral take: the content is its own neutral, as style transfer from
// one styled clip has it).
enum class TransferNeutral { kTake, kContent };
constexpr double kMinStrength = -1.0;
constexpr double kMaxStrength = 2.0;

// A transfer's layers. With a neutral take, on takes [content, neutral, style_1, ..., style_n]:
// the content's layer at 1 and style i added from the neutral at s_i; with the content its own
// neutral, on takes [content, style_1, ..., style_n], style i added from the content. Throws
// InputError on no style or a strength outside [kMinStrength, kMaxStrength].
MixLayers transfer_layers(const std::vector<double>& strengths, TransferNeutral neutral = TransferNeutral::kTake);
// The per-take weights of transfer_layers: content 1, neutral -sum s_i (or the content 1 -
// sum s_i), style i s_i. Throws as transfer_layers.
std::vector<double> transfer_weights(const std::vector<double>& strengths,
                                     TransferNeutral neutral = TransferNeutral::kTake);

// Each take's weight for the whole body into `out` (`takes` of them): the sum of the layers'
// weights on it, an additive layer's taken from its `from`. Layers of takes outside
// [0, takes) are skipped (MixParams::Validate refuses them). No allocation once `out` is sized.
// O(layers).
void take_weights(const MixLayers& layers, int takes, std::vector<double>& out);
std::vector<double> take_weights(const MixLayers& layers, int takes);
// The same per component into `out` (components x takes), a layer without weights per
// component giving its weight to each; empty (0 x 0) when no layer has them. No allocation once
// `out` is sized. O(components x layers).
void take_component_weights(const MixLayers& layers, int takes, int components, Eigen::MatrixXd& out);

}  // namespace mostyle
