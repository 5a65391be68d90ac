#include "ui/model/document_mix.h"

#include <algorithm>
#include <string>
#include <optional>
#include <filesystem>
#include <cctype>
#include <iterator>
#include <limits>
#include <utility>

#include "ui/model/keyed_weights.h"

namespace mostyle::ui {
namespace {

// The layers' weights per component the document mixes (k x takes): each layer's own there, else
// its weight (`weights`, constant_weights); empty unless weights per part are on, in shared mode,
// with a layer that has them for these takes.
Eigen::MatrixXd mixed_component_weights(const Document& document, const Decomposed& d, const std::vector<double>& weights) {
  Eigen::MatrixXd w;
  const std::vector<TakeLayer>& layers = document.layers;
  const bool any = std::any_of(layers.begin(), layers.end(), [](const TakeLayer& l) { return !l.component_weights.empty(); });
  if (!document.controls.per_part || d.shared() == nullptr || layers.size() != weights.size() || !any) return w;
  w.resize(d.components(), static_cast<Eigen::Index>(layers.size()));
  for (Eigen::Index c = 0; c < w.rows(); ++c)
    for (size_t i = 0; i < layers.size(); ++i) {
      const std::vector<std::optional<double>>& own = layers[i].component_weights;
      const size_t at = static_cast<size_t>(c);
      w(c, static_cast<Eigen::Index>(i)) = at < own.size() && own[at] ? *own[at] : weights[i];
    }
  return w;
}

// A transfer's layers: the content's (take 0) at 1, each style (every take but the content and
// the neutral) added from the neutral at its strength (weights[i]), per component its column of
// `parts` when there are parts.
MixLayers transfer_layers_of(const std::vector<double>& weights, const Eigen::MatrixXd& parts, int neutral) {
  MixLayers layers;
  layers.layers.push_back(MixLayer{0, 1.0, {}});
  for (int i = 1; i < static_cast<int>(weights.size()); ++i) {
    if (i == neutral) continue;
    AdditiveLayer style{i, neutral, weights[static_cast<size_t>(i)], {}};
    if (parts.size() > 0) style.component_weights.assign(parts.col(i).data(), parts.col(i).data() + parts.rows());
    layers.additive.push_back(std::move(style));
  }
  return layers;
}

}  // namespace

MixParams mix_params_for(const Document& document, const Decomposed& decomposition, int takes) {
  const DocumentControls& c = document.controls;
  MixParams m;
  const std::vector<double> weights = constant_weights(document, takes);
  const Eigen::MatrixXd parts = mixed_component_weights(document, decomposition, weights);
  set_mix_keys(c, takes, m.keys);  // style over time, when keyed
  if (c.transfer) {
    // The content is the reference (take 0); each style adds its change from the neutral take (or
    // from the content, when it is its own neutral), as `transfer` does: the content keeps its
    // path and its planted feet.
    const int neutral = transfer_neutral(c, takes);
    m.layers = transfer_layers_of(weights, parts, neutral);
    m.min_weight = transfer_min_weight(takes);
    m.max_weight = transfer_max_weight(takes);
    m.feet_of_reference = true;
    m.reference_cycles = true;
    m.path_leash = transfer_path_leash(neutral == 0 ? TransferNeutral::kContent : TransferNeutral::kTake, c.timing_a);
  } else {
    m.layers = take_layers(weights, parts);
  }
  const int levels = decomposition.params.basic_motions;
  m.swap_level = levels > 0 ? std::clamp(c.swap_level, 0, levels - 1) : 0;
  m.reference_timing = c.timing_a;
  m.residual = c.residual;
  m.finish.foot_lock = c.foot_lock;
  m.finish.loop = c.loop;
  m.Validate(takes, decomposition.components());
  return m;
}

std::optional<std::vector<double>> values_for_takes(const std::vector<std::string>& before,
                                                    const std::vector<double>& values,
                                                    const std::vector<std::string>& after, double added) {
  const bool fit = values.size() == before.size() && !before.empty();
  if (!fit) return std::nullopt;
  if (same_files(before, after)) return values;
  const bool added_at_end = after.size() > before.size() &&
                            same_files(before, std::vector<std::string>(after.begin(), after.begin() + before.size()));
  if (!added_at_end) return std::nullopt;
  std::vector<double> out = values;
  out.resize(after.size(), added);
  return out;
}

std::vector<double> weights_for_takes(const std::vector<std::string>& before, const std::vector<double>& weights,
                                      const std::vector<std::string>& after) {
  return values_for_takes(before, weights, after, 0.0)
      .value_or(std::vector<double>(after.size(), 1.0 / static_cast<double>(after.size())));
}

int named_neutral(const std::vector<std::string>& files) {
  for (size_t k = 1; k < files.size(); ++k) {
    std::string stem = std::filesystem::path(files[k]).stem().string();
    std::transform(stem.begin(), stem.end(), stem.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    // A word of the name, as takes are named (walk_neutral, bye-normal, Neutral01): not "abnormal".
    for (const char* word : {"neutral", "normal"}) {
      const size_t at = stem.find(word);
      if (at == std::string::npos) continue;
      const bool starts = at == 0 || !std::isalpha(static_cast<unsigned char>(stem[at - 1]));
      const size_t end = at + std::char_traits<char>::length(word);
      const bool ends = end == stem.size() || !std::isalpha(static_cast<unsigned char>(stem[end]));
      if (starts && ends) return static_cast<int>(k);
    }
  }
  return -1;
}

std::vector<TakeLayer> layers_for_takes(const std::vector<std::string>& before, const std::vector<TakeLayer>& layers,
                                        const std::vector<std::string>& after) {
  std::vector<double> weights;
  for (const TakeLayer& layer : layers) weights.push_back(layer.weight);
  const std::optional<std::vector<double>> kept = values_for_takes(before, weights, after, 0.0);
  std::vector<TakeLayer> out;
  if (!kept) {
    for (double w : weights_for_takes(before, weights, after)) out.push_back(TakeLayer{w, {}});
    return out;
  }
  out = layers;
  // A layer added: weight 0 everywhere, so that the result stays as it was.
  TakeLayer added;
  for (const TakeLayer& layer : layers) {
    added.component_weights.resize(std::max(added.component_weights.size(), layer.component_weights.size()));
    for (size_t c = 0; c < layer.component_weights.size(); ++c)
      if (layer.component_weights[c]) added.component_weights[c] = 0.0;
  }
  out.resize(after.size(), added);
  return out;
}

void size_transfer_controls(DocumentControls& controls, const std::vector<std::string>& before,
                            const std::vector<std::string>& after) {
  const int takes = static_cast<int>(after.size());
  // The takes before, or takes added to them: the neutral stays; new takes: the one named so.
  const std::vector<double> one_each(before.size(), 0.0);
  if (!values_for_takes(before, one_each, after, 0.0)) {
    const int neutral = named_neutral(after);
    controls.content_neutral = neutral < 0;
    if (neutral >= 0) controls.neutral = neutral;
  }
  controls.neutral = std::clamp(controls.neutral, 1, std::max(1, takes - 1));
}

void fit_component_weights(Document& document, const Decomposed& decomposition) {
  DocumentControls& c = document.controls;
  const std::vector<TakeLayer>& layers = document.layers;
  if (std::all_of(layers.begin(), layers.end(), [](const TakeLayer& l) { return l.component_weights.empty(); })) return;
  std::vector<BodyRegion> regions;
  for (const ComponentJoints& joints : decomposition.component_joints) regions.push_back(joints.region);
  const size_t k = regions.size();
  for (TakeLayer& layer : document.layers) {
    std::vector<std::optional<double>>& own = layer.component_weights;
    if (own.empty() || c.component_regions == regions) continue;
    if (c.component_regions.size() != own.size()) {  // regions not known: kept by index
      own.resize(k);
      continue;
    }
    std::vector<std::optional<double>> fitted(k);
    for (size_t i = 0; i < k; ++i) {
      const auto first = std::find(c.component_regions.begin(), c.component_regions.end(), regions[i]);
      if (first != c.component_regions.end()) fitted[i] = own[static_cast<size_t>(first - c.component_regions.begin())];
    }
    own = std::move(fitted);
  }
  c.component_regions = std::move(regions);
}

}  // namespace mostyle::ui
