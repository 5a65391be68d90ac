#include "ui/model/engine_link.h"

#include <algorithm>

#include "ui/model/document_fields.h"
#include "ui/model/document_mix.h"
#include "ui/model/recent_files.h"

namespace mostyle::ui {
namespace {

// The decomposition the document asks for (a level's sparsity not set yet: the main one).
DecomposeParams decompose_params_for(const Document& document) {
  const DocumentControls& c = document.controls;
  DecomposeParams p;
  p.mode = c.mode;
  p.components = document.parameters.components;
  p.sparsity = document.parameters.sparsity;
  if (p.mode == DecompositionMode::kPaper && c.basic_motions > 0) {
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

EngineLink::EngineLink(const BvhReadOptions& read)
    : worker_(read), sweep_(read), snapshot_(worker_.snapshot()) {}
EngineLink::~EngineLink() = default;

void EngineLink::load_files(const std::vector<std::string>& paths, WeightsOf weights) {
  requested_files_.clear();
  for (const std::string& path : paths)
    if (!path.empty() || requested_files_.empty()) requested_files_.push_back(path);
  load_waiting_ = true;
  weights_of_ = weights;
}

std::vector<std::string> EngineLink::requested_takes() const {
  if (requested_a().empty()) return {};
  std::vector<std::string> takes = requested_files_;
  if (takes.size() == 1) takes.push_back(takes[0]);  // A with itself
  return takes;
}

void EngineLink::load(const std::string& path_a, const std::string& path_b) { load_files({path_a, path_b}); }

PrepareOptions EngineLink::prepare_options(const Document& document) const {
  PrepareOptions o;
  o.align = document.controls.align;
  return o;
}

void EngineLink::request_decomposition(const Document& document) {
  requested_ = decompose_params_for(document);
  worker_.decompose(requested_);
}

void EngineLink::sync(EditorState& state, bool item_held) {
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
    worker_.load(requested_files_, prepare_options(d));  // a take alone: with itself
  } else if (realign && snapshot_->prepared) {
    worker_.load(snapshot_->paths, prepare_options(d));
  }
  update_result(state, item_held);
}

bool EngineLink::decomposition_outdated() const {
  return !snapshot_->decomposed || !same_decomposition(snapshot_->decompose_params, requested_);
}

void EngineLink::set_wake(std::function<void()> wake) {
  wake_ = std::move(wake);
  worker_.set_on_change(wake_);
  sweep_.set_wake(wake_);
}

bool EngineLink::has_news() const {
  if (worker_.snapshot()->version != seen_version_) return true;
  return sweep_.has_news();
}

void EngineLink::poll(EditorState& state) {
  sweep_.poll();
  auto snap = worker_.snapshot();
  if (snap->version == seen_version_) return;
  seen_version_ = snap->version;
  snapshot_ = std::move(snap);
  // The takes before: the weights were theirs, unless the load said they are the new takes'.
  const std::vector<std::string> files_before = state.document.files;
  // The document's takes are those loaded (a load that failed leaves them as they were).
  state.document.files = snapshot_->prepared ? snapshot_->paths : std::vector<std::string>();
  if (takes() != seen_prepared_) {
    seen_prepared_ = takes();
    if (takes() != nullptr) {  // the layers follow the takes, one rule for any number of them
      const std::vector<std::string>& layers_of = weights_of_ == WeightsOf::kNewTakes ? snapshot_->paths : files_before;
      state.document.layers = layers_for_takes(layers_of, state.document.layers, snapshot_->paths);
      size_transfer_controls(state.document.controls, layers_of, snapshot_->paths);
      weights_of_ = WeightsOf::kLoadedTakes;
    }
    take_up_takes(state);
  }
  const Decomposed* d = takes() != nullptr ? snapshot_->decomposed.get() : nullptr;
  if (d != nullptr && d != seen_decomposed_) {
    seen_decomposed_ = d;
    take_up_decomposition(state);
  }
}

// New takes: the takes and their result shown, and they join the recent takes; the error curve
// of the previous takes goes.
void EngineLink::take_up_takes(EditorState& state) {
  state.shown.clear();
  state.cycle_provenance.clear();  // of the previous takes' result
  sweep_.clear();
  view_.clear();
  const PreparedTakes* p = takes();
  if (p == nullptr) return;
  // Remembered once loaded: a mistyped path never joins the recent takes. The first is the newest.
  for (auto path = snapshot_->paths.rbegin(); path != snapshot_->paths.rend(); ++path)
    remember(state.recent.takes, *path, kRecentTakes);
  view_.take_up(*p, snapshot_->paths, snapshot_->warnings, state);
}

// A new decomposition: the layers' weights per component fitted to its components, and its point
// on the error curve (the curve for new takes, sparsity or mode computed in the background).
void EngineLink::take_up_decomposition(EditorState& state) {
  const Decomposed* d = seen_decomposed_;
  DocumentControls& c = state.document.controls;
  if (d->shared() != nullptr) fit_component_weights(state.document, *d);
  if (c.selected_component >= d->components()) c.selected_component = -1;
  sweep_.add(*d, seen_prepared_, snapshot_->paths, prepare_options(asked_));
}

void EngineLink::update_result(EditorState& state, bool item_held) {
  if (const PreparedTakes* p = takes()) view_.update(*p, snapshot_->decomposed.get(), state, item_held);
}

void EngineLink::wait_idle(EditorState& state) {
  sync(state);
  worker_.wait_idle();
  poll(state);  // a new decomposition starts the error sweep
  sweep_.wait_idle();
  poll(state);
  sync(state);
}

}  // namespace mostyle::ui
