#pragma once
// The engine's worker thread: runs loading, preprocessing, decomposition and synthesis off the
// caller's thread, for a pair of takes (pipeline.h) or a palette of several (palette.h). A request
// replaces pending work of its stage; a running job that a request makes stale is cancelled at its
// next check. Results are immutable snapshots, readable at any time from any thread. Every
// exception becomes an error sentence in the snapshot; what was loaded before an error stays.
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "engine/io/bvh_io.h"
#include "engine/io/job_control.h"
#include "engine/run/palette.h"
#include "engine/run/pipeline.h"

namespace mostyle {

// Holds a pair or a palette, never both: a successful load of one clears the other's fields.
struct WorkerSnapshot {
  // The pair.
  std::shared_ptr<const PreparedTakes> prepared;     // null unless a pair is loaded
  std::shared_ptr<const Decomposed> decomposed;  // of `prepared`; null until its first one
  std::shared_ptr<const BlendResult> blend;          // of `decomposed` with blend_params
  // The parameters of the request `decomposed` (or `palette_decomposition`) was made from. A
  // palette is decomposed in shared mode without basic motions whatever this says; its
  // decomposition's own params hold what it used.
  DecomposeParams decompose_params;
  BlendParams blend_params;                          // the parameters `blend` was made with
  std::string path_a, path_b;                        // files of `prepared`
  // The palette.
  std::shared_ptr<const PreparedTakes> palette;                    // null unless a palette is loaded
  std::shared_ptr<const Decomposed> palette_decomposition;  // of `palette`; null until its first one
  std::shared_ptr<const MixResult> mix;                               // of `palette_decomposition` with mix_params
  MixParams mix_params;                                               // the parameters `mix` was made with
  std::vector<std::string> palette_paths;                             // files of `palette`, the reference first
  std::string error;                  // the last failed request's sentence; empty after a success
  std::vector<std::string> warnings;  // from loading `prepared` or `palette`
  std::uint64_t version = 0;          // grows with every published change
};

// A palette's stages run as the pair's: kLoading (read and prepare_takes), kDecomposing, and
// kBlending (mix_palette).
enum class WorkerStage { kIdle, kLoading, kDecomposing, kBlending };
const char* worker_stage_name(WorkerStage stage);  // "idle", "loading", ...

struct WorkerStatus {
  WorkerStage stage = WorkerStage::kIdle;
  float progress = 0.0f;  // 0..1 of the running stage
  bool pending = false;   // requests wait behind the running one
};

class Worker {
 public:
  // Every take it loads is read with `read` (its memory limit: the editor passes the one
  // MOSTYLE_MAX_MEMORY_MB sets, as the CLI does).
  explicit Worker(const BvhReadOptions& read = {});
  ~Worker();  // cancels the running job and joins the thread
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;

  // Loads and prepares a pair (path_b empty: A with itself), then decomposes and blends with the
  // current parameters. Replaces a pending load (pair or palette); cancels a running load or
  // decomposition. A success clears the palette.
  void load(const std::string& path_a, const std::string& path_b, const PrepareOptions& options = {});
  // Loads and prepares a palette of 2 to kMaxPaletteTakes takes (paths[0] the reference; a path
  // given twice is read once), then decomposes it with the current parameters (in shared mode
  // without basic motions, which are the pair's) and mixes it with the current mix parameters;
  // when their weights are not one per take, the mix parameters become equal weights (and no
  // per-component weights). Replaces a pending load (pair or palette); cancels a running load or
  // decomposition. A success clears the pair. Cost: reading the files, then one prepare_takes.
  void load_palette(const std::vector<std::string>& paths, const PrepareOptions& options = {});
  // New decomposition parameters: re-decomposes and re-blends the pair, or re-decomposes and
  // re-mixes the palette. Cancels a running decomposition.
  void decompose(const DecomposeParams& params);
  // New blend parameters: re-runs the pair's synthesis and post-processing only.
  void blend(const BlendParams& params);
  // New mix parameters: re-runs the palette's mix_palette only. Parameters mix_palette refuses
  // (weights of the wrong count or not summing to 1, ...) become the snapshot's error and the
  // previous mix stays.
  void mix(const MixParams& params);

  std::shared_ptr<const WorkerSnapshot> snapshot() const;
  WorkerStatus status() const;
  // Blocks until nothing is running or pending (tests, batch use, screenshots).
  void wait_idle() const;
  // Called on the worker's thread after each job (a load, a decomposition, a blend or mix, a
  // failure or a cancellation), once its snapshot and status are published, so that an event
  // loop waiting for input can wake and show it. Empty: none. Must be safe to call from another
  // thread (a GLFW empty event is); it may read the snapshot and the status.
  void set_on_change(std::function<void()> notify);

 private:
  void run();
  // The jobs run() picks from: each is called with `lock` held, unlocks it while it works and
  // holds it again when it returns (an exception may leave it unlocked; run() relocks).
  void run_load(std::unique_lock<std::mutex>& lock);
  void run_load_palette(std::unique_lock<std::mutex>& lock);
  void run_decompose(std::unique_lock<std::mutex>& lock);
  void run_decompose_palette(std::unique_lock<std::mutex>& lock);
  void run_blend(std::unique_lock<std::mutex>& lock);
  void run_mix(std::unique_lock<std::mutex>& lock);
  bool has_work() const;  // with mutex_ held: a request that can run now
  void publish(const std::function<void(WorkerSnapshot&)>& change);

  mutable std::mutex mutex_;
  mutable std::condition_variable wake_;
  mutable std::condition_variable idle_;
  bool stop_ = false;
  bool need_load_ = false, need_decompose_ = false, need_blend_ = false, need_mix_ = false;
  bool load_is_palette_ = false;  // the pending load is palette_paths_, not path_a_ and path_b_
  std::string path_a_, path_b_;
  std::vector<std::string> palette_paths_;
  const BvhReadOptions read_options_;  // set before the thread starts, never changed
  PrepareOptions prepare_options_;
  DecomposeParams decompose_params_;
  BlendParams blend_params_;
  MixParams mix_params_;
  WorkerStage running_ = WorkerStage::kIdle;
  JobControl control_;
  std::shared_ptr<const WorkerSnapshot> snapshot_;
  std::function<void()> on_change_;
  std::thread thread_;
};

}  // namespace mostyle
