#include "ui/model/blend_session.h"
#include "ui/model/take_warnings.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <iterator>

#include "engine/base/clock.h"
#include "engine/io/motion_file.h"
#include "engine/base/error.h"
#include "engine/export/channel_layout.h"
#include "engine/export/export_solve.h"
#include "ui/model/cycle_provenance.h"
#include "ui/model/document_fields.h"
#include "ui/model/export_job.h"
#include "ui/model/joint_contacts.h"
#include "ui/model/keyed_weights.h"
#include "ui/model/lanes.h"
#include "ui/model/weight_keys_edit.h"

namespace mostyle::ui {
namespace {

// A warm orange, a sky blue and a green: A, B, and the blend between them.
const glm::vec3 kColorA(0.96f, 0.60f, 0.28f);
const glm::vec3 kColorB(0.36f, 0.64f, 0.97f);
const glm::vec3 kColorBlend(0.50f, 0.88f, 0.46f);
const glm::vec4 kHighlight(1.0f, 0.92f, 0.25f, 1.0f);
constexpr size_t kRecentFiles = 8;

using Clock = std::chrono::steady_clock;
std::string stem(const std::string& path) { return take_label(path); }

// The decomposition the document asks for (a level's sparsity not set yet: the main one).
DecomposeParams decompose_params_for(const Document& document) {
  const DocumentControls& c = document.controls;
  DecomposeParams p;
  p.mode = c.mode;
  p.components = document.parameters.components;
  p.sparsity = document.parameters.sparsity;
  if (p.mode == BlendMode::kPaper && c.basic_motions > 0) {
    p.basic_motions = c.basic_motions;
    p.basic_sparsities = c.basic_sparsities;
    p.basic_sparsities.resize(static_cast<size_t>(p.basic_motions), p.sparsity);
  }
  return p;
}

// Whether two requests ask for the same decomposition (what the sliders set; not the solver's
// iterations or tolerance).
bool same_decomposition(const DecomposeParams& x, const DecomposeParams& y) {
  return x.mode == y.mode && x.components == y.components && x.sparsity == y.sparsity &&
         x.basic_motions == y.basic_motions && x.basic_sparsities == y.basic_sparsities;
}

}  // namespace

BlendSession::BlendSession(const BvhReadOptions& read) : read_(read), worker_(read), snapshot_(worker_.snapshot()) {}
BlendSession::~BlendSession() = default;

void BlendSession::load_files(const std::vector<std::string>& paths) {
  if (paths.size() <= 2) {
    load(paths.empty() ? std::string() : paths[0], paths.size() > 1 ? paths[1] : std::string());
    return;
  }
  requested_files_ = paths;
  requested_a_ = paths[0];
  requested_b_ = paths[1];
  load_waiting_ = true;
}

void BlendSession::load(const std::string& path_a, const std::string& path_b) {
  requested_a_ = path_a;
  requested_b_ = path_b;
  requested_files_ = {path_a};
  if (!path_b.empty()) requested_files_.push_back(path_b);
  load_waiting_ = true;
}

PrepareOptions BlendSession::prepare_options(const Document& document) const {
  PrepareOptions o;
  o.align = document.controls.align;
  return o;
}

void BlendSession::request_decomposition(const Document& document) {
  requested_ = decompose_params_for(document);
  worker_.decompose(requested_);
}

void BlendSession::sync(EditorState& state, bool item_held) {
  const Document& d = state.document;
  // What the document's change since the worker was last asked makes stale (document_fields.h),
  // once nothing is held. The decomposition first: a load decomposes with the parameters last
  // asked for.
  const bool realign = !item_held && differs_at(asked_, d, Stale::kAlignment);
  if (!item_held) {
    if (differs_at(asked_, d, Stale::kDecomposition)) request_decomposition(d);
    asked_ = d;
  }
  if (load_waiting_) {  // a command: given now, with the document's alignment
    load_waiting_ = false;
    asked_.controls.align = d.controls.align;
    std::vector<std::string> paths = requested_files_;
    if (paths.size() == 1) paths.push_back(paths[0]);  // A with itself
    worker_.load(paths, prepare_options(d));
  } else if (realign && snapshot_->prepared) {
    worker_.load(snapshot_->paths, prepare_options(d));
  }
  update_blend(state);
}

// Remembered once loaded: a mistyped path never joins the recent files. paths: first the newest.
void BlendSession::remember_recent(const std::vector<std::string>& paths) {
  for (auto path = paths.rbegin(); path != paths.rend(); ++path) {
    if (path->empty()) continue;
    recent_.erase(std::remove(recent_.begin(), recent_.end(), *path), recent_.end());
    recent_.push_front(*path);
  }
  while (recent_.size() > kRecentFiles) recent_.pop_back();
}

void BlendSession::set_recent(const std::vector<std::string>& paths) {
  recent_.assign(paths.begin(), paths.end());
  while (recent_.size() > kRecentFiles) recent_.pop_back();
}

bool BlendSession::decomposition_outdated() const {
  return !snapshot_->decomposed || !same_decomposition(snapshot_->decompose_params, requested_);
}

void BlendSession::start_error_sweep(const DecomposeParams& base) {
  if (pair() == nullptr) return;
  sweep_params_ = base;
  sweep_params_.components = kSweepComponents[0];
  sweep_next_ = 0;
  sweep_worker_ = std::make_unique<Worker>(read_);  // the previous one (if any) is cancelled and joined
  sweep_seen_version_ = 0;
  if (wake_) sweep_worker_->set_on_change(wake_);
  sweep_worker_->decompose(sweep_params_);
  sweep_worker_->load(snapshot_->paths, prepare_options(asked_));
}

void BlendSession::set_wake(std::function<void()> wake) {
  wake_ = std::move(wake);
  worker_.set_on_change(wake_);
  if (sweep_worker_) sweep_worker_->set_on_change(wake_);
}

bool BlendSession::has_news() const {
  if (worker_.snapshot()->version != seen_version_) return true;
  return sweep_next_ >= 0 && sweep_worker_ && sweep_worker_->snapshot()->version != sweep_seen_version_;
}

void BlendSession::poll_sweep() {
  if (sweep_next_ < 0 || !sweep_worker_) return;
  auto snap = sweep_worker_->snapshot();
  sweep_seen_version_ = snap->version;
  if (!snap->error.empty()) {  // e.g. k larger than the channels: the sweep stops there
    sweep_next_ = -1;
    return;
  }
  const Decomposed* d = snap->decomposed.get();
  if (d == nullptr || d->params.components != sweep_params_.components) return;
  ErrorPoint point{d->params.components, d->params.sparsity, d->params.mode, d->rmse[0], d->rmse[1]};
  auto same = [&](const ErrorPoint& e) {
    return e.components == point.components && e.sparsity == point.sparsity && e.mode == point.mode;
  };
  if (std::find_if(error_curve_.begin(), error_curve_.end(), same) == error_curve_.end()) {
    error_curve_.push_back(point);
    std::sort(error_curve_.begin(), error_curve_.end(),
              [](const ErrorPoint& a, const ErrorPoint& b) { return a.components < b.components; });
  }
  if (++sweep_next_ >= static_cast<int>(std::size(kSweepComponents))) {
    sweep_next_ = -1;
    return;
  }
  sweep_params_.components = kSweepComponents[sweep_next_];
  sweep_worker_->decompose(sweep_params_);
}

void BlendSession::poll(EditorState& state) {
  poll_sweep();
  auto snap = worker_.snapshot();
  if (snap->version == seen_version_) return;
  seen_version_ = snap->version;
  snapshot_ = std::move(snap);
  // The takes before, with their weights: a take added keeps the others' weights (below).
  const std::vector<std::string> files_before = state.document.files;
  std::vector<double> weights_before = state.document.controls.palette.weights;
  if (files_before.size() == 2) weights_before = {1.0 - state.document.parameters.alpha, state.document.parameters.alpha};
  // The document's takes are those loaded (a load that failed leaves them as they were).
  state.document.files = snapshot_->prepared ? snapshot_->paths : std::vector<std::string>();
  if (pair() != seen_prepared_) {
    seen_prepared_ = pair();
    take_up_prepared(state);
  }
  if (palette() != seen_palette_) {
    seen_palette_ = palette();
    palette_view_.clear();
    if (seen_palette_ != nullptr) {
      remember_recent(snapshot_->paths);
      std::vector<double> kept = weights_with_added_takes(files_before, weights_before, snapshot_->paths);
      if (!kept.empty()) state.document.controls.palette.weights = std::move(kept);
      palette_view_.take_up(*seen_palette_, snapshot_->paths, snapshot_->warnings, state.document.controls.palette,
                            state);
    }
  }
  const Decomposed* d = pair() != nullptr ? snapshot_->decomposed.get() : nullptr;
  if (d != nullptr && d != seen_decomposed_) {
    seen_decomposed_ = d;
    DocumentControls& c = state.document.controls;  // sized to the decomposition's k
    c.component_alpha.resize(static_cast<size_t>(d->components()), state.document.parameters.alpha);
    if (c.selected_component >= d->components()) c.selected_component = -1;
    ErrorPoint point{d->params.components, d->params.sparsity, d->params.mode, d->rmse[0], d->rmse[1]};
    auto same = [&](const ErrorPoint& e) {
      return e.components == point.components && e.sparsity == point.sparsity && e.mode == point.mode;
    };
    error_curve_.erase(std::remove_if(error_curve_.begin(), error_curve_.end(), same), error_curve_.end());
    error_curve_.push_back(point);
    std::sort(error_curve_.begin(), error_curve_.end(),
              [](const ErrorPoint& a, const ErrorPoint& b) { return a.components < b.components; });
    // A new pair, sparsity or mode: the curve for it is computed in the background.
    const bool same_curve = sweep_params_.mode == d->params.mode && sweep_params_.sparsity == d->params.sparsity &&
                            sweep_params_.basic_motions == d->params.basic_motions;
    if (!same_curve || !sweep_worker_ || sweep_pair_ != seen_prepared_) {
      sweep_pair_ = seen_prepared_;
      start_error_sweep(d->params);
    }
  }
}

// A new pair: the three takes on A's timeline, the placement, the DTW image.
void BlendSession::take_up_prepared(EditorState& state) {
  const PreparedTakes* p = pair();
  if (p == nullptr && palette() != nullptr) return;  // the palette's view has the takes
  state.takes.clear();
  state.cycle_provenance.clear();  // of the previous takes' result
  error_curve_.clear();  // of the previous pair
  has_blend_ = false;
  export_message_.clear();  // it spoke of the previous takes
  export_ok_ = false;
  blended_decomposed_ = nullptr;
  if (p == nullptr) return;
  remember_recent(snapshot_->paths);
  const int joints = static_cast<int>(p->majors.size());
  auto make = [&](const std::string& label, const glm::vec3& color, const Eigen::MatrixXd& contacts) {
    Take t;
    t.label = label;
    t.color = color;
    t.clip = p->takes[0].clip;
    t.fps = p->fps;
    t.parents = p->parents;
    t.contacts = joint_contacts(contacts, p->feet, joints);
    return t;
  };
  Take a = make("A  " + stem(loaded_path(0)), kColorA, p->takes[0].own_contacts);
  a.path = loaded_path(0);
  Take b = make("B  " + stem(loaded_path(1)), kColorB, Eigen::MatrixXd());
  b.path = loaded_path(1);
  // Each take's load warnings under it, and what could not be matched well under the take it
  // speaks of: where the takes are listed, not only in the DTW view.
  std::vector<std::vector<std::string>> warnings =
      warnings_by_take({a.path, b.path}, snapshot_->warnings, {{}, p->takes[1].alignment.warnings}, {"A", "B"});
  a.warnings = std::move(warnings[0]);
  b.warnings = std::move(warnings[1]);
  Take blend = make("blend", kColorBlend, Eigen::MatrixXd());
  blend.path = "(blend of A and B)";
  blend.positions = p->takes[0].world;  // until the first blend arrives
  state.takes = {std::move(a), std::move(b), std::move(blend)};

  // Shared floor and start, side-by-side spacing and direction (ui/model/lanes.h).
  const Placement placed = placement_of(p->takes[0].world);
  shift_ = placed.shift;
  side_ = placed.side;
  spacing_ = placed.spacing;
  for (Take& t : state.takes) t.size = placed.size;
  placed_overlay_ = state.document.overlay;
  place(state);
  compute_dtw_image();
}

// Writes every take's positions from the engine's matrices with the current placement, all on
// the blend's timeline: A and B are shown where the blend is in each of them (the mix's
// sources), so the three stay in step whatever the timing. Before the first blend,
// the warp's own samples. Slots across the travel: A left, the blend in the middle, B right.
void BlendSession::place(EditorState& state) {
  const PreparedTakes* p = pair();
  if (p == nullptr || state.takes.size() != 3) return;
  const TimeWarp& warp = p->takes[1].alignment.warp;
  if (has_blend_) {
    source_a_ = blend_.sources.col(0);
    source_b_ = blend_.sources.col(1);
  }
  const Eigen::VectorXd& at_a = has_blend_ ? source_a_ : warp.a;
  const Eigen::VectorXd& at_b = has_blend_ ? source_b_ : warp.b;
  sample_rows(p->takes[0].world, at_a, shown_a_);
  sample_rows(p->takes[1].world_placed, at_b, shown_b_);
  const int joints = static_cast<int>(p->majors.size());
  auto nearest = [](const Eigen::MatrixXd& contacts, const Eigen::VectorXd& at) {
    Eigen::MatrixXd out(at.size(), contacts.cols());
    for (Eigen::Index k = 0; k < at.size(); ++k)
      out.row(k) = contacts.row(std::clamp<Eigen::Index>(std::lround(at[k]), 0, contacts.rows() - 1));
    return out;
  };
  state.takes[kTakeA].contacts = joint_contacts(nearest(p->takes[0].own_contacts, at_a), p->feet, joints);
  state.takes[kTakeB].contacts = joint_contacts(nearest(p->takes[1].own_contacts, at_b), p->feet, joints);
  state.takes[kTakeA].cycle_starts = cycle_starts_at(p->takes[0].timeline_cycles(), at_a);
  state.takes[kTakeB].cycle_starts = cycle_starts_at(p->takes[1].timeline_cycles(), at_b);
  state.takes[kTakeBlend].cycle_starts = state.takes[kTakeA].cycle_starts;  // the blend walks A's cycles
  const double slots[3] = {-1.0, 1.0, 0.0};  // A, B, blend
  const Eigen::MatrixXd* sources[3] = {&shown_a_, &shown_b_, has_blend_ ? &blend_.motion.world : &shown_a_};
  if (!state.document.overlay && has_blend_) {
    // Side by side: A and B in lanes beside the blend's path (ui/model/lanes.h).
    const Lanes lanes = lanes_along(blend_.motion.world, Eigen::Vector2d(side_.x(), side_.z()));
    for (int t = 0; t < 3; ++t) {
      Eigen::MatrixXd& out = state.takes[static_cast<size_t>(t)].positions;
      if (t == kTakeBlend) {
        out = blend_.motion.world;
        for (Eigen::Index j = 0; 3 * j < out.cols(); ++j)
          for (int a = 0; a < 3; ++a) out.col(3 * j + a).array() += shift_[a];
      } else {
        place_in_lane(*sources[t], lanes, slots[t] * spacing_, shift_, out);
      }
    }
    placed_overlay_ = state.document.overlay;
    return;
  }
  for (int t = 0; t < 3; ++t) {
    const Eigen::Vector3d offset = shift_ + (state.document.overlay ? 0.0 : slots[t] * spacing_) * side_;
    Eigen::MatrixXd& out = state.takes[static_cast<size_t>(t)].positions;
    out = *sources[t];
    for (Eigen::Index j = 0; 3 * j < out.cols(); ++j)
      for (int a = 0; a < 3; ++a) out.col(3 * j + a).array() += offset[a];
  }
  placed_overlay_ = state.document.overlay;
}

void BlendSession::update_blend(EditorState& state) {
  if (const PreparedTakes* p = palette()) {
    palette_view_.update(*p, snapshot_->decomposed.get(), state.document.controls, state);
    return;
  }
  const PreparedTakes* p = pair();
  const Decomposed* d = snapshot_->decomposed.get();
  if (p == nullptr || state.takes.size() != 3) return;
  DocumentControls& controls = state.document.controls;
  if (d != nullptr) {
    BlendParams params;
    params.alpha = state.document.parameters.alpha;
    if (d->params.mode == BlendMode::kShared && controls.per_component) {
      controls.component_alpha.resize(static_cast<size_t>(d->components()), params.alpha);
      params.component_alpha = controls.component_alpha;
    }
    params.swap_level = d->params.basic_motions > 0 ? std::clamp(controls.swap_level, 0, d->params.basic_motions - 1) : 0;
    params.foot_lock = controls.foot_lock;
    params.timing_a = controls.timing_a;
    params.loop = controls.loop;
    params.residual = controls.residual;
    set_mix_keys(controls, 2, keys_);  // style over time, when keyed (the mix's weights over the output)
    const bool changed = d != blended_decomposed_ || !same_keys(keys_, blended_keys_) ||
                         params.alpha != blended_params_.alpha ||
                         params.timing_a != blended_params_.timing_a || params.loop != blended_params_.loop ||
                         params.residual != blended_params_.residual ||
                         params.component_alpha != blended_params_.component_alpha ||
                         params.swap_level != blended_params_.swap_level || params.foot_lock != blended_params_.foot_lock;
    if (changed) {
      const auto t0 = Clock::now();
      try {
        set_blend_mix_params(params, *d, blend_mix_);
        blend_mix_.keys = keys_;  // blend_params.h speaks of one alpha: the keys are the mix's
        mix_palette(*p, *d, blend_mix_, scratch_, blend_, &blend_times_);
        has_blend_ = true;
        // Where each of its cycles came from, for the timeline's tooltip: once per blend.
        state.cycle_provenance = cycle_provenance(*p, blend_.sources, {"A", "B"});
        blend_error_.clear();
      } catch (const std::exception& e) {  // InputError: a bad parameter, shown as it is
        blend_error_ = e.what();
      }
      blend_ms_ = ms_since(t0);
      blended_decomposed_ = d;
      blended_params_ = params;
      blended_keys_ = keys_;
      refresh_blend_take(state);
    }
  }
  if (placed_overlay_ != state.document.overlay) place(state);

  // The selected component's joints light up on the blend.
  Take& blend = state.takes[kTakeBlend];
  blend.highlights.clear();
  const int c = controls.selected_component;
  if (d != nullptr && c >= 0 && c < d->support.rows()) {
    blend.highlights.assign(blend.parents.size(), glm::vec4(0.0f));
    for (size_t j = 0; j < blend.parents.size() && 3 * j + 2 < static_cast<size_t>(d->support.cols()); ++j) {
      const Eigen::Index col = 3 * static_cast<Eigen::Index>(j);
      if (d->support(c, col) != 0 || d->support(c, col + 1) != 0 || d->support(c, col + 2) != 0)
        blend.highlights[j] = kHighlight;
    }
  }
}

void BlendSession::refresh_blend_take(EditorState& state) {
  const PreparedTakes* p = pair();
  Take& t = state.takes[kTakeBlend];
  char label[64];
  if (state.document.controls.per_component && snapshot_->decomposed && snapshot_->decomposed->params.mode == BlendMode::kShared)
    std::snprintf(label, sizeof label, "blend (per component)");
  else if (!blended_keys_.empty())
    std::snprintf(label, sizeof label, "blend  alpha keyed");
  else
    std::snprintf(label, sizeof label, "blend  alpha %.2f", state.document.parameters.alpha);
  t.label = label;
  if (has_blend_) t.contacts = joint_contacts(blend_.motion.contacts, p->feet, static_cast<int>(p->majors.size()));
  place(state);
}

void BlendSession::wait_idle(EditorState& state) {
  sync(state);
  worker_.wait_idle();
  poll(state);  // a new decomposition starts the error sweep
  while (sweep_next_ >= 0 && sweep_worker_) {  // each step's next request is made by poll_sweep
    sweep_worker_->wait_idle();
    poll_sweep();
  }
  poll(state);
  sync(state);
}

// Local cost c(i, j) = |a_i - b_j| (the DTW's, engine/align/dtw.h) at the centre of each cell: O(cells), not
// O(F x Fb), so a long take does not stall the frame that takes it up.
void BlendSession::compute_dtw_image() {
  dtw_image_ = DtwCostImage();
  const PreparedTakes* p = pair();
  if (p == nullptr) return;
  const Eigen::MatrixXd& fa = p->takes[1].alignment.feature.a;
  const Eigen::MatrixXd& fb = p->takes[1].alignment.feature.b;
  if (fa.rows() == 0 || fb.rows() == 0) return;
  DtwCostImage& img = dtw_image_;
  img.frames_a = static_cast<int>(fa.rows());
  img.frames_b = static_cast<int>(fb.rows());
  img.rows = std::min(img.frames_a, DtwCostImage::kMaxCells);
  img.cols = std::min(img.frames_b, DtwCostImage::kMaxCells);
  img.cost.resize(img.rows, img.cols);
  for (int r = 0; r < img.rows; ++r) {
    const int i = std::min(img.frames_a - 1, static_cast<int>((r + 0.5) * img.frames_a / img.rows));
    for (int c = 0; c < img.cols; ++c) {
      const int j = std::min(img.frames_b - 1, static_cast<int>((c + 0.5) * img.frames_b / img.cols));
      img.cost(r, c) = static_cast<float>((fa.row(i) - fb.row(j)).norm());
    }
  }
  const float top = img.cost.maxCoeff();
  if (top > 0.0f) img.cost /= top;
}

bool BlendSession::export_bvh(const std::string& path) {
  ExportOutcome outcome;
  try {
    ExportOptions options;
    options.path = path;
    const PreparedTakes* p = pair();
    if (p != nullptr) options.fps = p->fps;  // the blend's own frames
    if (p != nullptr && p->takes[0].clip != nullptr) options.layout = default_channel_layout(*p->takes[0].clip);
    outcome = run_export(make_export_request(*this, options));
  } catch (const std::exception& e) {  // InputError: no file name, no blend yet
    outcome.message = e.what();
  }
  set_export_result(outcome.ok, outcome.message, outcome.ok ? outcome.ms : export_ms_);
  return export_ok_;
}

void BlendSession::set_export_result(bool ok, const std::string& message, double ms) {
  export_ok_ = ok;
  export_message_ = message;
  export_ms_ = ms;
}

}  // namespace mostyle::ui
