#include "ui/model/palette_view.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "engine/base/clock.h"
#include "engine/io/motion_file.h"
#include "engine/base/error.h"
#include "ui/model/blend_session.h"
#include "ui/model/cycle_provenance.h"
#include "ui/model/joint_contacts.h"
#include "ui/model/keyed_weights.h"
#include "ui/model/lanes.h"
#include "ui/model/take_warnings.h"
#include "ui/model/weight_keys_edit.h"

namespace mostyle::ui {
namespace {

const glm::vec3 kMixColor(0.50f, 0.88f, 0.46f);

using Clock = std::chrono::steady_clock;
// The parts the palette panel gives weights to, in PaletteControls::part_weights order.
constexpr BodyPart kParts[] = {BodyPart::kLegs, BodyPart::kArms, BodyPart::kSpine};

bool same_mix(const MixParams& a, const MixParams& b) {
  return a.weights == b.weights && same_keys(a.keys, b.keys) && a.component_weights.rows() == b.component_weights.rows() &&
         a.component_weights.cols() == b.component_weights.cols() && a.component_weights == b.component_weights &&
         a.min_weight == b.min_weight && a.max_weight == b.max_weight && a.reference_timing == b.reference_timing &&
         a.residual == b.residual && a.finish.limb_lengths == b.finish.limb_lengths &&
         a.finish.foot_lock == b.finish.foot_lock && a.finish.loop == b.finish.loop;
}

}  // namespace

glm::vec3 palette_color(int take) {
  // A and B keep the pair's orange and blue; then violet, yellow, pink, teal, ... around the wheel.
  static const glm::vec3 kColors[] = {{0.96f, 0.60f, 0.28f}, {0.36f, 0.64f, 0.97f}, {0.74f, 0.52f, 0.96f},
                                      {0.95f, 0.85f, 0.30f}, {0.96f, 0.45f, 0.66f}, {0.30f, 0.85f, 0.80f},
                                      {0.80f, 0.80f, 0.80f}, {0.62f, 0.80f, 0.35f}};
  return kColors[static_cast<size_t>(take) % (sizeof kColors / sizeof kColors[0])];
}

MixParams mix_params_for(const DocumentControls& controls, const Decomposed& decomposition, int takes) {
  const PaletteControls& c = controls.palette;
  MixParams m;
  // A transfer: content is the reference (take 0); the neutral take (or the content, when it is
  // its own neutral) loses what each style gains.
  m.weights = palette_weights(c, takes);
  set_mix_keys(controls, takes, m.keys);  // style over time, when keyed
  if (c.transfer) {
    m.min_weight = transfer_min_weight(takes);
    m.max_weight = transfer_max_weight(takes);
    m.feet_of_reference = true;
  }
  if (c.per_part && !c.transfer) {
    // Each part: its own weights when given (one per take), else the overall weights.
    std::vector<std::pair<BodyPart, std::vector<double>>> given;
    for (size_t part = 0; part < c.part_weights.size() && part < std::size(kParts); ++part)
      if (static_cast<int>(c.part_weights[part].size()) == takes) given.emplace_back(kParts[part], c.part_weights[part]);
    if (!given.empty()) m.component_weights = part_weights(given, decomposition.component_joints, m.weights);
  }
  m.reference_timing = controls.timing_a;
  m.residual = controls.residual;
  m.finish.foot_lock = controls.foot_lock;
  m.finish.loop = controls.loop;
  m.Validate(takes, decomposition.components());
  return m;
}

std::vector<double> weights_with_added_takes(const std::vector<std::string>& before, const std::vector<double>& weights,
                                             const std::vector<std::string>& after) {
  if (after.size() <= before.size() || weights.size() != before.size()) return {};
  std::vector<double> out(after.size(), 0.0);
  std::vector<bool> used(before.size(), false);  // a file given twice: each its own weight
  bool kept = false;
  for (size_t i = 0; i < after.size(); ++i)
    for (size_t j = 0; j < before.size(); ++j)
      if (!used[j] && before[j] == after[i]) {
        used[j] = true;
        out[i] = weights[j];
        kept = true;
        break;
      }
  return kept ? out : std::vector<double>();
}

void PaletteView::clear() {
  has_mix_ = false;
  mixed_decomposition_ = nullptr;
  error_.clear();
}

void PaletteView::take_up(const PreparedTakes& p, const std::vector<std::string>& paths,
                          const std::vector<std::string>& warnings, PaletteControls& controls, EditorState& state) {
  clear();
  const int n = p.size();
  if (static_cast<int>(controls.weights.size()) != n) controls.weights.assign(static_cast<size_t>(n), 1.0 / n);
  if (static_cast<int>(controls.strengths.size()) != n) controls.strengths.assign(static_cast<size_t>(n), 1.0);
  controls.part_weights.resize(std::size(kParts));
  for (auto& w : controls.part_weights)
    if (static_cast<int>(w.size()) != n) w.clear();  // empty: the part follows the overall weights
  controls.neutral = std::clamp(controls.neutral, 1, n - 1);
  state.takes.clear();
  state.cycle_provenance.clear();  // of the previous takes' result
  names_.clear();
  Take mix;
  mix.label = "mix";
  mix.path = "(mix of the palette's takes)";
  mix.color = kMixColor;
  mix.clip = p.takes.front().clip;
  mix.fps = p.fps;
  mix.parents = p.parents;
  mix.positions = p.takes.front().world_placed;  // until the first mix arrives
  state.takes.push_back(std::move(mix));
  // Each take's load warnings and alignment onto the reference under it (prepare_takes names a
  // palette's takes by their files' names).
  std::vector<std::vector<std::string>> aligned;
  std::vector<std::string> aligned_names;
  for (const PreparedTake& take : p.takes) {
    aligned.push_back(take.alignment.warnings);
    aligned_names.push_back(std::filesystem::path(take.clip->source).filename().string());
  }
  std::vector<std::string> take_paths = paths;
  take_paths.resize(static_cast<size_t>(n));
  std::vector<std::vector<std::string>> by_take = warnings_by_take(take_paths, warnings, aligned, aligned_names);
  for (int i = 0; i < n; ++i) {
    Take t;
    const std::string& path = static_cast<size_t>(i) < paths.size() ? paths[static_cast<size_t>(i)] : std::string();
    t.path = path;
    t.label = (i == 0 ? "reference  " : "") + take_label(path);
    names_.push_back(take_label(path));
    t.color = palette_color(i);
    t.clip = p.takes[static_cast<size_t>(i)].clip;
    t.fps = p.fps;
    t.parents = p.parents;
    t.warnings = std::move(by_take[static_cast<size_t>(i)]);
    state.takes.push_back(std::move(t));
  }
  // Shared floor and start, side-by-side spacing and direction (ui/model/lanes.h).
  const Placement placed = placement_of(p.takes.front().world_placed);
  shift_ = placed.shift;
  side_ = placed.side;
  spacing_ = placed.spacing;
  for (Take& t : state.takes) t.size = placed.size;
}

void PaletteView::update(const PreparedTakes& p, const Decomposed* d, const DocumentControls& controls,
                         EditorState& state) {
  if (static_cast<int>(state.takes.size()) != p.size() + 1) return;
  if (d != nullptr) {
    try {
      const MixParams params = mix_params_for(controls, *d, p.size());
      if (d != mixed_decomposition_ || !same_mix(params, mixed_)) {
        const auto t0 = Clock::now();
        mix_palette(p, *d, params, scratch_, mix_, &mix_times_);
        mix_ms_ = ms_since(t0);
        has_mix_ = true;
        error_.clear();
        // Where each of its cycles came from, for the timeline's tooltip: once per mix.
        state.cycle_provenance = cycle_provenance(p, mix_.sources, names_);
        mixed_decomposition_ = d;
        mixed_ = params;
        char label[64];
        std::snprintf(label, sizeof label, controls.palette.transfer ? "transfer" : "mix");
        state.takes[kPaletteMix].label = label;
        state.takes[kPaletteMix].contacts =
            joint_contacts(mix_.motion.contacts, p.feet, static_cast<int>(p.majors.size()));
        place(p, controls, state);
      }
    } catch (const std::exception& e) {  // refused weights: said in the palette panel, the last mix stays
      error_ = e.what();
      mixed_decomposition_ = d;
    }
  }
  if (placed_overlay_ != state.document.overlay || placed_ghosts_ != controls.palette.ghosts) place(p, controls, state);
}

// Every take at the frame the mix shows of it, on the reference's floor: the reference left of
// the mix, the other takes (ghosts, on demand) to its right, or all on one spot when overlaid.
void PaletteView::place(const PreparedTakes& p, const DocumentControls& controls, EditorState& state) {
  const int n = p.size();
  const bool ghosts = controls.palette.ghosts;
  Eigen::MatrixXd sampled;
  // Side by side: every take in a lane beside the mix's path (ui/model/lanes.h).
  const bool lanes_on = !state.document.overlay && has_mix_;
  Lanes lanes;
  if (lanes_on) lanes = lanes_along(mix_.motion.world, Eigen::Vector2d(side_.x(), side_.z()));
  for (int i = -1; i < n; ++i) {
    Take& t = state.takes[static_cast<size_t>(kPaletteFirst + i)];
    const double slot = i < 0 ? 0.0 : i == 0 ? -1.0 : double(i);
    if (i < 0) {
      if (has_mix_) sampled = mix_.motion.world;
      else continue;
    } else {
      const PreparedTake& take = p.takes[static_cast<size_t>(i)];
      if (has_mix_) sample_rows(take.world_placed, mix_.sources.col(i), sampled);
      else sampled = take.world_placed;
      t.visible = i == 0 || ghosts;
      if (has_mix_) {
        t.cycle_starts = cycle_starts_at(take.timeline_cycles(), mix_.sources.col(i));
        if (i == 0) state.takes[kPaletteMix].cycle_starts = t.cycle_starts;  // the mix walks the reference's cycles
      }
    }
    if (lanes_on && i >= 0) {
      place_in_lane(sampled, lanes, slot * spacing_, shift_, t.positions);
      continue;
    }
    const Eigen::Vector3d offset = shift_ + (state.document.overlay ? 0.0 : slot * spacing_) * side_;
    t.positions = sampled;
    for (Eigen::Index j = 0; 3 * j < t.positions.cols(); ++j)
      for (int a = 0; a < 3; ++a) t.positions.col(3 * j + a).array() += offset[a];
  }
  placed_overlay_ = state.document.overlay;
  placed_ghosts_ = ghosts;
}

}  // namespace mostyle::ui
