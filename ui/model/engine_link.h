#pragma once
// The editor's link to the engine. Owns the engine Worker; each frame poll() takes up its latest
// snapshot (a new pair, a new decomposition, an error) and sync() brings the engine to the
// document (EditorState::document): what a change to it makes stale (ui/model/document_fields.h)
// is done again, and nothing more: the takes aligned again, the decomposition asked for again
// (both on the worker), or the result mixed again on the UI thread when a weight moved
// (ResultView: the viewport follows in the same frame). The panels only edit the document; loads
// are commands (load_files). Nothing here blocks, except wait_idle(), for tests and screenshots.
//
// EditorState::takes while takes are loaded (ResultView, ui/model/result_view.h): take i at i,
// the reference first, and the result last, all on the result's timeline.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "engine/worker/worker.h"
#include "ui/model/editor_state.h"
#include "ui/model/error_sweep.h"
#include "ui/model/result_view.h"

namespace mostyle::ui {

// Whose layers the document holds (Document::layers) when a load is asked for: the takes loaded
// now (a take added, replaced or removed: the new takes' layers follow from them by
// layers_for_takes, ui/model/document_mix.h), or the new takes' already (undo, a session, a new
// order of the takes, the command line: kept when they are one per take).
enum class WeightsOf { kLoadedTakes, kNewTakes };

class EngineLink {
 public:
  // Takes are read with `read` (the editor passes the memory limit MOSTYLE_MAX_MEMORY_MB sets).
  explicit EngineLink(const BvhReadOptions& read = {});
  ~EngineLink();
  EngineLink(const EngineLink&) = delete;
  EngineLink& operator=(const EngineLink&) = delete;

  // Asks for the takes `paths`, 2 to 16 (one: the take with itself; the first the reference),
  // mixed with the document's layers, taken as `weights` says once the takes arrive. What was
  // loaded stays until it succeeds; a failure shows up as error() on a later poll(). The paths
  // join the recent takes once they loaded. The worker is asked at the next sync(), with the
  // document's alignment options then. An empty path after the first is left out.
  void load_files(const std::vector<std::string>& paths, WeightsOf weights = WeightsOf::kLoadedTakes);
  // load_files({a, b}), in a pair's words (b empty: A with itself).
  void load(const std::string& path_a, const std::string& path_b);
  // A load asked for that the worker has not been given yet (the next sync() gives it).
  bool load_waiting() const { return load_waiting_; }
  // The files last asked for, loaded or not.
  const std::vector<std::string>& requested_files() const { return requested_files_; }
  // Those files as the worker is given them and a Document lists them: a take alone twice (A
  // with itself); empty before any load (or when the first path asked for was empty).
  std::vector<std::string> requested_takes() const;
  // The takes loaded (any number), or null.
  const PreparedTakes* takes() const { return snapshot_->prepared.get(); }
  // The file of loaded take i ("" when there is none).
  const std::string& loaded_path(size_t i) const {
    static const std::string kNone;
    return i < snapshot_->paths.size() ? snapshot_->paths[i] : kNone;
  }
  const ResultView& result_view() const { return view_; }
  // Before the panels, once per frame: takes up a new snapshot (new takes: rebuilds the takes
  // shown and sets the document's files to them, and its layers: layers_for_takes).
  void poll(EditorState& state);
  // After the panels (and before them, after poll, with item_held): brings the engine to the
  // document. A load waiting goes to the worker; an alignment option that changed aligns the
  // takes again; k, sparsity, the mode or the basic motions that changed ask for a decomposition,
  // but not while item_held (an ImGui item is held: k's slider decomposes once, when let go);
  // then the result is mixed again when its inputs changed (ResultView: a preview while
  // item_held, finished once let go), and the takes shown follow.
  void sync(EditorState& state, bool item_held = false);
  // sync(), then blocks until the worker is idle (tests, screenshots), then poll() + sync().
  void wait_idle(EditorState& state);

  // Called on a worker's thread whenever one of them finishes a job (engine Worker::set_on_change),
  // so a window waiting for input wakes to show it; the window passes a thread-safe wake-up.
  void set_wake(std::function<void()> wake);
  // A worker has published something poll() has not taken up yet: the next frame differs.
  bool has_news() const;

  const WorkerSnapshot& snapshot() const { return *snapshot_; }
  WorkerStatus status() const { return worker_.status(); }
  const std::string& error() const { return snapshot_->error; }
  // The result shown (a blend, mix or transfer), or null before the first.
  const MixResult* result() const { return view_.mix(); }
  // The direction the takes stand apart in side by side (x, 0, z, unit: across the reference's
  // overall travel, ui/model/lanes.h); +X before any takes.
  Eigen::Vector3d side() const { return view_.side(); }
  // Why the document's weights or keys were refused (the last result stays), or "".
  const std::string& result_error() const { return view_.error(); }
  const std::vector<ErrorPoint>& error_curve() const { return sweep_.curve(); }
  // Reconstruction error against k (ui/model/error_sweep.h) of the takes loaded, being computed
  // in the background.
  bool sweeping() const { return sweep_.sweeping(); }

  // The decomposition the panels' sliders ask for differs from the one shown.
  bool decomposition_outdated() const;

  // The first file last asked for, the reference, loaded or not ("" when there is none).
  const std::string& requested_a() const {
    static const std::string kNone;
    return requested_files_.empty() ? kNone : requested_files_[0];
  }

 private:
  PrepareOptions prepare_options(const Document& document) const;
  void request_decomposition(const Document& document);
  void update_result(EditorState& state, bool item_held);
  void take_up_takes(EditorState& state);
  void take_up_decomposition(EditorState& state);

  Worker worker_;
  std::function<void()> wake_;            // set_wake(); given to the sweep worker too
  ErrorSweep sweep_;                      // the error curve's own worker
  std::shared_ptr<const WorkerSnapshot> snapshot_;
  std::uint64_t seen_version_ = ~std::uint64_t(0);
  const PreparedTakes* seen_prepared_ = nullptr;
  const Decomposed* seen_decomposed_ = nullptr;
  DecomposeParams requested_;   // the decomposition last asked of the worker
  Document asked_;               // the document as the worker was last asked for it (sync)
  bool load_waiting_ = false;    // load_files() since the last sync()
  WeightsOf weights_of_ = WeightsOf::kLoadedTakes;  // of the load last asked for, until its takes arrive
  std::vector<std::string> requested_files_;
  ResultView view_;
};


}  // namespace mostyle::ui
