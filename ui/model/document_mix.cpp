#include "ui/model/document_mix.h"

#include <algorithm>
#include <iterator>
#include <limits>
#include <utility>

#include "engine/run/blend_params.h"
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
  set_component_alpha_weights(alphas, w);
  return w;
}

}  // namespace

MixParams mix_params_for(const Document& document, const Decomposed& decomposition, int takes) {
  const DocumentControls& controls = document.controls;
  const PaletteControls& c = controls.palette;
  MixParams m;
  m.weights = constant_weights(document, takes);
  set_mix_keys(controls, takes, m.keys);  // style over time, when keyed
  if (takes == 2) {
    // A pair's weights: any value (how far to exaggerate is the person's call), and its alphas
    // per component when asked for.
    m.min_weight = -std::numeric_limits<double>::infinity();
    m.max_weight = std::numeric_limits<double>::infinity();
    m.component_weights = component_alpha_weights(document, decomposition);
    // A pair's transfer: B's style on A, A its own neutral, as `transfer A --style B` (the
    // weights are the same: 1 - alpha and alpha).
    if (c.transfer) {
      m.feet_of_reference = true;
      m.path_leash = transfer_path_leash(TransferNeutral::kContent);
    }
  } else if (c.transfer) {
    // A transfer: content is the reference (take 0); the neutral take (or the content, when it
    // is its own neutral) loses what each style gains.
    m.min_weight = transfer_min_weight(takes);
    m.max_weight = transfer_max_weight(takes);
    m.feet_of_reference = true;
    m.path_leash = transfer_path_leash(c.content_neutral ? TransferNeutral::kContent : TransferNeutral::kTake);
  } else if (c.per_part) {
    // Each part: its own weights when given (one per take), else the overall weights.
    std::vector<std::pair<BodyPart, std::vector<double>>> given;
    for (size_t part = 0; part < c.part_weights.size() && part < std::size(kParts); ++part)
      if (static_cast<int>(c.part_weights[part].size()) == takes) given.emplace_back(kParts[part], c.part_weights[part]);
    if (!given.empty()) m.component_weights = part_weights(given, decomposition.component_joints, m.weights);
  }
  const int levels = decomposition.params.basic_motions;
  m.swap_level = levels > 0 ? std::clamp(controls.swap_level, 0, levels - 1) : 0;
  m.reference_timing = controls.timing_a;
  m.residual = controls.residual;
  m.finish.foot_lock = controls.foot_lock;
  m.finish.loop = controls.loop;
  m.Validate(takes, decomposition.components());
  return m;
}

std::vector<double> weights_for_takes(const std::vector<std::string>& before, const std::vector<double>& weights,
                                      const std::vector<std::string>& after) {
  const bool fit = weights.size() == before.size() && !before.empty();
  if (fit && same_files(before, after)) return weights;
  const bool added_at_end = after.size() > before.size() &&
                            same_files(before, std::vector<std::string>(after.begin(), after.begin() + before.size()));
  if (fit && added_at_end) {
    std::vector<double> out = weights;
    out.resize(after.size(), 0.0);
    return out;
  }
  return std::vector<double>(after.size(), 1.0 / static_cast<double>(after.size()));
}

void size_palette_controls(PaletteControls& controls, int takes) {
  const size_t n = static_cast<size_t>(takes);
  if (controls.strengths.size() != n) controls.strengths.assign(n, 1.0);
  controls.part_weights.resize(std::size(kParts));
  for (auto& w : controls.part_weights)
    if (w.size() != n) w.clear();  // empty: the part follows the overall weights
  controls.neutral = std::clamp(controls.neutral, 1, std::max(1, takes - 1));
}

}  // namespace mostyle::ui
