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

// The parts the palette panel gives weights to, in PaletteControls::part_weights order.
constexpr BodyPart kParts[] = {BodyPart::kLegs, BodyPart::kArms, BodyPart::kSpine};

// A pair's per-component alphas as weights (1 - alpha_c, alpha_c), k x 2 (a component without
// an alpha of its own yet takes alpha); none unless the components are shared and asked for one
// by one.
Eigen::MatrixXd component_alpha_weights(const Document& document, const Decomposed& d) {
  const DocumentControls& c = document.controls;
  Eigen::MatrixXd w;
  if (d.shared() == nullptr || !c.per_component) return w;
  std::vector<double> alphas = c.component_alpha;
  alphas.resize(static_cast<size_t>(d.components()), pair_alpha(document));
  w.resize(static_cast<Eigen::Index>(alphas.size()), 2);
  for (size_t k = 0; k < alphas.size(); ++k) w.row(static_cast<Eigen::Index>(k)) << 1.0 - alphas[k], alphas[k];
  return w;
}

}  // namespace

MixParams mix_params_for(const Document& document, const Decomposed& decomposition, int takes) {
  const DocumentControls& controls = document.controls;
  const PaletteControls& c = controls.palette;
  MixParams m;
  const std::vector<double> weights = constant_weights(document, takes);
  Eigen::MatrixXd component_weights;
  set_mix_keys(controls, takes, m.keys);  // style over time, when keyed
  if (takes == 2) {
    // A pair's weights: any value (how far to exaggerate is the person's call), and its alphas
    // per component when asked for.
    m.min_weight = -std::numeric_limits<double>::infinity();
    m.max_weight = std::numeric_limits<double>::infinity();
    component_weights = component_alpha_weights(document, decomposition);
    // A pair's transfer: B's style on A, A its own neutral, as `transfer A --style B` (the
    // weights are the same: 1 - alpha and alpha).
    if (c.transfer) {
      m.feet_of_reference = true;
      m.path_leash = transfer_path_leash(TransferNeutral::kContent, controls.timing_a);
    }
  } else if (c.transfer) {
    // A transfer: content is the reference (take 0); the neutral take (or the content, when it
    // is its own neutral) loses what each style gains.
    m.min_weight = transfer_min_weight(takes);
    m.max_weight = transfer_max_weight(takes);
    m.feet_of_reference = true;
    m.path_leash = transfer_path_leash(c.content_neutral ? TransferNeutral::kContent : TransferNeutral::kTake, controls.timing_a);
  } else if (c.per_part) {
    // Each part: its own weights when given (one per take), else the overall weights.
    std::vector<std::pair<BodyPart, std::vector<double>>> given;
    for (size_t part = 0; part < c.part_weights.size() && part < std::size(kParts); ++part)
      if (static_cast<int>(c.part_weights[part].size()) == takes) given.emplace_back(kParts[part], c.part_weights[part]);
    if (!given.empty()) component_weights = part_weights(given, decomposition.component_joints, weights);
  }
  m.layers = take_layers(weights, component_weights);
  const int levels = decomposition.params.basic_motions;
  m.swap_level = levels > 0 ? std::clamp(controls.swap_level, 0, levels - 1) : 0;
  m.reference_timing = controls.timing_a;
  m.residual = controls.residual;
  m.finish.foot_lock = controls.foot_lock;
  m.finish.loop = controls.loop;
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

void size_palette_controls(PaletteControls& controls, const std::vector<std::string>& before,
                           const std::vector<double>& weights_before, const std::vector<std::string>& after) {
  const size_t n = after.size();
  const int takes = static_cast<int>(n);
  // A pair's transfer keeps its strength in the pair's alpha (B's weight): B's strength once it
  // is a palette.
  std::vector<double> strengths = controls.strengths;
  if (strengths.size() != before.size() && before.size() == 2 && weights_before.size() == 2 && controls.transfer)
    strengths = {1.0, weights_before[1]};
  // Takes added keep every value there was and start neutral themselves (strength and weights 0).
  if (const auto kept = values_for_takes(before, strengths, after, 0.0)) {
    controls.strengths = *kept;
  } else if (controls.strengths.size() != n) {  // new takes: full strength, and a neutral as named
    controls.strengths.assign(n, 1.0);
    const int neutral = named_neutral(after);
    controls.content_neutral = neutral < 0;
    if (neutral >= 0) controls.neutral = neutral;
  }
  controls.part_weights.resize(std::size(kParts));
  for (auto& w : controls.part_weights) {
    const auto kept = values_for_takes(before, w, after, 0.0);
    w = kept ? *kept : std::vector<double>();  // empty: the part follows the overall weights
  }
  controls.neutral = std::clamp(controls.neutral, 1, std::max(1, takes - 1));
}

}  // namespace mostyle::ui
