#include "ui/model/result_view.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "engine/base/clock.h"
#include "engine/io/motion_file.h"
#include "ui/model/cycle_provenance.h"
#include "ui/model/document_fields.h"
#include "ui/model/document_mix.h"
#include "ui/model/joint_contacts.h"
#include "ui/model/lanes.h"
#include "ui/model/take_warnings.h"
#include "ui/model/weight_keys_edit.h"

namespace mostyle::ui {
namespace {

// A take shown at a mix's sources, where the mix left a cycle slot out (MixResult::slot_skips):
// its frames after it are its own timeline's past the slot, which it walked on over; moved back
// along the ground so that it goes on from where it was, one frame's step on, as the result does.
void close_slot_skips(const std::vector<Eigen::Index>& skips, Eigen::MatrixXd& rows) {
  for (Eigen::Index k : skips) {
    if (k < 2 || k >= rows.rows()) continue;
    const double dx = 2.0 * rows(k - 1, 0) - rows(k - 2, 0) - rows(k, 0);
    const double dz = 2.0 * rows(k - 1, 2) - rows(k - 2, 2) - rows(k, 2);
    for (Eigen::Index j = 0; 3 * j < rows.cols(); ++j) {
      rows.block(k, 3 * j, rows.rows() - k, 1).array() += dx;
      rows.block(k, 3 * j + 2, rows.rows() - k, 1).array() += dz;
    }
  }
}

}  // namespace

namespace {

const glm::vec4 kHighlight(1.0f, 0.92f, 0.25f, 1.0f);

using Clock = std::chrono::steady_clock;

// Take i's short name among `takes`: its letter in a pair (take_letter), else its label (the
// animation's name, or its file's): how the result's provenance names it.
std::string short_name(int i, int takes, const std::string& path) {
  const char* letter = take_letter(i, takes);
  return *letter ? letter : take_label(path);
}

// How the engine's alignment warnings name take i of `takes` (prepare_takes: A and B for a
// pair, its file's name for more), so each warning is filed under its take.
std::string aligned_name(int i, int takes, const PreparedTake& take) {
  const char* letter = take_letter(i, takes);
  return *letter ? letter : std::filesystem::path(take.clip->source).filename().string();
}

// Take i's label in the takes list and the viewport: its letter before its label in a pair
// ("A  happy"), "reference  normal" for the first of more, and then each take's own name.
std::string take_caption(int i, int takes, const std::string& path) {
  const char* letter = take_letter(i, takes);
  const std::string lead = *letter ? std::string(letter) + "  " : i == 0 ? "reference  " : "";
  return lead + take_label(path);
}

// The result's label: what it is (result_name), per part or keyed; a pair's also says its alpha
// (a pair's transfer its strength), the one number that tells a pair's result.
std::string result_caption(const Document& d, const Decomposed* decomposition, int takes) {
  const bool transfer = d.controls.transfer;
  const std::string name = result_name(takes, transfer);
  const bool shared = decomposition != nullptr && decomposition->params.mode == DecompositionMode::kShared;
  if (d.controls.per_part && shared) return name + " (per part)";
  const bool keyed = !d.controls.keys.empty() && keys_fit(d.controls.keys, takes);
  const char* amount = transfer ? "strength" : "alpha";
  if (takes != 2) return keyed ? name + "  keyed" : name;  // only a pair has one number to say, its alpha
  if (keyed) return name + "  " + amount + " keyed";
  char label[64];
  std::snprintf(label, sizeof label, "%s  %s %.2f", name.c_str(), amount, pair_alpha(d));
  return label;
}

// Frames of a take's per-frame rows at the (fractional) frames `at`, rounded to the nearest.
Eigen::MatrixXd nearest_rows(const Eigen::MatrixXd& rows, const Eigen::VectorXd& at) {
  Eigen::MatrixXd out(at.size(), rows.cols());
  for (Eigen::Index k = 0; k < at.size(); ++k)
    out.row(k) = rows.row(std::clamp<Eigen::Index>(std::lround(at[k]), 0, rows.rows() - 1));
  return out;
}

}  // namespace

glm::vec3 take_color(int take) {
  static const glm::vec3 kColors[] = {{0.96f, 0.60f, 0.28f}, {0.36f, 0.64f, 0.97f}, {0.74f, 0.52f, 0.96f},
                                      {0.95f, 0.85f, 0.30f}, {0.96f, 0.45f, 0.66f}, {0.30f, 0.85f, 0.80f},
                                      {0.80f, 0.80f, 0.80f}, {0.62f, 0.80f, 0.35f}};
  return kColors[static_cast<size_t>(take) % (sizeof kColors / sizeof kColors[0])];
}

glm::vec3 result_color() { return {0.50f, 0.88f, 0.46f}; }

ShownMotion shown_take(std::string label, glm::vec3 color, std::shared_ptr<const Clip> clip, double fps,
                std::vector<int> parents, Eigen::MatrixXd positions) {
  ShownMotion t;
  t.label = std::move(label);
  t.color = color;
  t.clip = std::move(clip);
  t.fps = fps;
  t.parents = std::move(parents);
  t.positions = std::move(positions);
  return t;
}

void ResultView::clear() {
  has_mix_ = false;
  mixed_decomposition_ = nullptr;
  error_.clear();
}

void ResultView::take_up(const PreparedTakes& p, const std::vector<std::string>& paths,
                         const std::vector<std::string>& warnings, EditorState& state) {
  clear();
  const int n = p.size();
  state.shown.clear();
  state.cycle_provenance.clear();  // of the previous takes' result
  names_.clear();
  // Each take's load warnings and its alignment onto the reference under it.
  std::vector<std::vector<std::string>> aligned;
  std::vector<std::string> aligned_names;
  for (int i = 0; i < n; ++i) {
    const PreparedTake& take = p.takes[static_cast<size_t>(i)];
    aligned.push_back(i == 0 ? std::vector<std::string>() : take.alignment.warnings);
    aligned_names.push_back(aligned_name(i, n, take));
  }
  std::vector<std::string> take_paths = paths;
  take_paths.resize(static_cast<size_t>(n));
  std::vector<TakeMessages> by_take = warnings_by_take(take_paths, warnings, aligned, aligned_names);
  const int joints = static_cast<int>(p.majors.size());
  for (int i = 0; i < n; ++i) {
    const PreparedTake& take = p.takes[static_cast<size_t>(i)];
    const std::string& path = take_paths[static_cast<size_t>(i)];
    // Its positions until the first result arrives.
    ShownMotion t = shown_take(take_caption(i, n, path), take_color(i), take.clip, p.fps, p.parents, take.world_placed);
    t.path = path;
    names_.push_back(short_name(i, n, t.path));
    t.warnings = std::move(by_take[static_cast<size_t>(i)].load);
    t.notes = std::move(by_take[static_cast<size_t>(i)].alignment);
    t.contacts = joint_contacts(take.own_contacts, p.feet, joints);
    state.shown.push_back(std::move(t));
  }
  const std::string name = result_name(n, state.document.controls.transfer);
  ShownMotion result = shown_take(name, result_color(), p.takes.front().clip, p.fps, p.parents, p.takes.front().world_placed);
  result.path = "(the " + name + " of the takes)";
  state.shown.push_back(std::move(result));
  // Shared floor and start, side-by-side spacing and direction (ui/model/lanes.h).
  const Placement placed = placement_of(p.takes.front().world_placed);
  shift_ = placed.shift;
  side_ = placed.side;
  spacing_ = placed.spacing;
  for (ShownMotion& t : state.shown) t.size = placed.size;
  place(p, state);
}

void ResultView::update(const PreparedTakes& p, const Decomposed* d, EditorState& state, bool item_held) {
  if (static_cast<int>(state.shown.size()) != p.size() + 1) return;
  if (d != nullptr && (d != mixed_decomposition_ || differs_at(mixed_, state.document, Stale::kMix)))
    remix(p, *d, state, item_held);
  else if (!item_held && previewing())
    finish(p, state);
  if (placed_overlay_ != state.document.overlay || placed_ghosts_ != state.document.controls.ghosts)
    place(p, state);
  highlight(d, state);
}

void ResultView::remix(const PreparedTakes& p, const Decomposed& d, EditorState& state, bool preview) {
  mixed_decomposition_ = &d;
  mixed_ = state.document;
  const auto t0 = Clock::now();
  try {
    mixed_params_ = mix_params_for(state.document, d, p.size());
    mixed_params_.preview = preview;
    mix_palette(p, d, mixed_params_, scratch_, mix_, &mix_times_);
  } catch (const std::exception& e) {  // refused weights or keys: said where they are set, the last result stays
    error_ = e.what();
    mix_ms_ = ms_since(t0);
    return;
  }
  mix_ms_ = ms_since(t0);
  has_mix_ = true;
  error_.clear();
  take_up_mix(p, state);
}

// A preview let go: the foot lock and the measures, on the mix shown.
void ResultView::finish(const PreparedTakes& p, EditorState& state) {
  const auto t0 = Clock::now();
  try {
    finish_mix_palette(p, mixed_params_, scratch_, mix_, &mix_times_);
  } catch (const std::exception& e) {
    error_ = e.what();
    return;
  }
  mix_ms_ += ms_since(t0);  // the preview and its finish: one mix
  take_up_mix(p, state);
}

// A new mix (or a preview finished) shown: the provenance of its cycles, the result's label and
// contacts, every take placed at the frame the result is in it.
void ResultView::take_up_mix(const PreparedTakes& p, EditorState& state) {
  const Decomposed& d = *mixed_decomposition_;
  // Where each of its cycles came from, for the timeline's tooltip: once per result.
  state.cycle_provenance = cycle_provenance(p, mix_.sources, names_);
  ShownMotion& result = state.shown[static_cast<size_t>(result_index(p.size()))];
  result.label = result_caption(state.document, &d, p.size());
  result.contacts = joint_contacts(mix_.motion.contacts, p.feet, static_cast<int>(p.majors.size()));
  place(p, state);
}

// Every take at the frame the result shows of it, on the reference's floor: the reference left of
// the result, the other takes to its right (a palette's on demand, as ghosts), or all on one spot
// when overlaid; side by side, each in a lane beside the result's path (ui/model/lanes.h).
void ResultView::place(const PreparedTakes& p, EditorState& state) {
  const int n = p.size();
  const bool overlay = state.document.overlay, ghosts = state.document.controls.ghosts;
  const int joints = static_cast<int>(p.majors.size());
  const bool lanes_on = !overlay && has_mix_;
  Lanes lanes;
  if (lanes_on) lanes = lanes_along(mix_.motion.world, Eigen::Vector2d(side_.x(), side_.z()));
  auto shift_by = [](Eigen::MatrixXd& rows, const Eigen::Vector3d& offset) {
    for (Eigen::Index j = 0; 3 * j < rows.cols(); ++j)
      for (int a = 0; a < 3; ++a) rows.col(3 * j + a).array() += offset[a];
  };
  ShownMotion& result = state.shown[static_cast<size_t>(result_index(n))];
  if (has_mix_) {
    result.positions = mix_.motion.world;
    shift_by(result.positions, shift_);
  }
  for (int i = 0; i < n; ++i) {
    const PreparedTake& take = p.takes[static_cast<size_t>(i)];
    ShownMotion& t = state.shown[static_cast<size_t>(i)];
    // The reference always stands beside the result; the other takes as ghosts.
    t.visible = i == 0 || ghosts;
    if (has_mix_) {
      const Eigen::VectorXd at = mix_.sources.col(i);
      sample_rows(take.world_placed, at, sampled_);
      close_slot_skips(mix_.slot_skips, sampled_);
      t.contacts = joint_contacts(nearest_rows(take.own_contacts, at), p.feet, joints);
      t.cycle_starts = cycle_starts_at(take.timeline_cycles(), at);
    } else {
      sampled_ = take.world_placed;
    }
    const double slot = i == 0 ? -1.0 : double(i);
    if (lanes_on) {
      place_in_lane(sampled_, lanes, slot * spacing_, shift_, t.positions);
    } else {
      t.positions = sampled_;
      shift_by(t.positions, shift_ + (overlay ? 0.0 : slot * spacing_) * side_);
    }
  }
  result.cycle_starts = state.shown.front().cycle_starts;  // the result walks the reference's cycles
  placed_overlay_ = overlay;
  placed_ghosts_ = ghosts;
}

// The selected component's joints light up on the result.
void ResultView::highlight(const Decomposed* d, EditorState& state) const {
  ShownMotion& result = state.shown.back();
  result.highlights.clear();
  const int c = state.document.controls.selected_component;
  if (d == nullptr || c < 0 || c >= d->support.rows()) return;
  result.highlights.assign(result.parents.size(), glm::vec4(0.0f));
  for (size_t j = 0; j < result.parents.size() && 3 * j + 2 < static_cast<size_t>(d->support.cols()); ++j) {
    const Eigen::Index col = 3 * static_cast<Eigen::Index>(j);
    if (d->support(c, col) != 0 || d->support(c, col + 1) != 0 || d->support(c, col + 2) != 0)
      result.highlights[j] = kHighlight;
  }
}

}  // namespace mostyle::ui
