#pragma once
// Reconstruction error against k, for the components view's curve: each decomposition the editor
// shows adds its point, and a second engine Worker decomposes the same takes (any number of them)
// at each k of kComponents (mode and sparsity as shown), one after the other, in the background.
// Never touches the result. No ImGui.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/worker/worker.h"

namespace mostyle::ui {

// One decomposition's reconstruction error.
struct ErrorPoint {
  int components = 0;
  double sparsity = 0.0;
  DecompositionMode mode = DecompositionMode::kShared;
  std::vector<double> rmse;           // each take's, in the order of the takes; the reference's units
};

class ErrorSweep {
 public:
  static constexpr int kComponents[] = {2, 4, 6, 8, 10, 12, 16, 20};

  // The sweep's takes are read with `read`, as the editor's own worker reads them.
  explicit ErrorSweep(const BvhReadOptions& read) : read_(read) {}

  // A decomposition shown for `takes` (read from `paths`, prepared with `options`): its point
  // joins the curve (replacing one at the same k, sparsity and mode), and new takes, sparsity,
  // mode or basic motions start the sweep again for them.
  void add(const Decomposed& d, const PreparedTakes* takes, const std::vector<std::string>& paths,
           const PrepareOptions& options);
  // New takes: the curve spoke of the previous ones.
  void clear() { curve_.clear(); }
  // Takes up the sweep worker's latest decomposition and asks for the next k. Once per frame.
  void poll();
  // The sweep worker has published something poll() has not taken up yet.
  bool has_news() const;
  // Blocks until the sweep has gone through every k (tests, screenshots).
  void wait_idle();
  // Called on the sweep worker's thread after each of its jobs (Worker::set_on_change).
  void set_wake(std::function<void()> wake);

  const std::vector<ErrorPoint>& curve() const { return curve_; }  // by k
  bool sweeping() const { return next_ >= 0; }

 private:
  void start(const DecomposeParams& base, const std::vector<std::string>& paths, const PrepareOptions& options);
  void insert(const ErrorPoint& point, bool replace);

  const BvhReadOptions read_;
  std::function<void()> wake_;
  std::unique_ptr<Worker> worker_;       // error against k, off the editor's worker
  std::uint64_t seen_version_ = 0;       // of worker_'s snapshot, at the last poll
  int next_ = -1;                        // index into kComponents being computed; -1: none
  DecomposeParams params_;               // the sweep's request now
  const PreparedTakes* swept_ = nullptr;  // the takes the sweep was started for
  std::vector<ErrorPoint> curve_;
};

}  // namespace mostyle::ui
