#pragma once
// The engine's worker thread: runs loading, preprocessing, decomposition and synthesis off the
// caller's thread. A request replaces pending work of its stage; a running job that a request
// makes stale is cancelled at its next check. Results are immutable snapshots, readable at any
// time from any thread. Every exception becomes an error sentence in the snapshot; what was
// loaded before an error stays.
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "engine/io/job_control.h"
#include "engine/run/pipeline.h"

namespace mostyle {

struct WorkerSnapshot {
  std::shared_ptr<const PreparedPair> prepared;      // null until a pair loaded
  std::shared_ptr<const DecomposedPair> decomposed;  // of `prepared`; null until its first one
  std::shared_ptr<const BlendResult> blend;          // of `decomposed` with blend_params
  DecomposeParams decompose_params;                  // the parameters `decomposed` was made with
  BlendParams blend_params;                          // the parameters `blend` was made with
  std::string path_a, path_b;                        // files of `prepared`
  std::string error;                  // the last failed request's sentence; empty after a success
  std::vector<std::string> warnings;  // from loading `prepared`
  std::uint64_t version = 0;          // grows with every published change
};

enum class WorkerStage { kIdle, kLoading, kDecomposing, kBlending };
const char* worker_stage_name(WorkerStage stage);  // "idle", "loading", ...

struct WorkerStatus {
  WorkerStage stage = WorkerStage::kIdle;
  float progress = 0.0f;  // 0..1 of the running stage
  bool pending = false;   // requests wait behind the running one
};

class Worker {
 public:
  Worker();
  ~Worker();  // cancels the running job and joins the thread
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;

  // Loads and prepares a pair (path_b empty: A with itself), then decomposes and blends with the
  // current parameters. Cancels a running load or decomposition.
  void load(const std::string& path_a, const std::string& path_b, const PrepareOptions& options = {});
  // New decomposition parameters: re-decomposes and re-blends. Cancels a running decomposition.
  void decompose(const DecomposeParams& params);
  // New blend parameters: re-runs synthesis and post-processing only.
  void blend(const BlendParams& params);

  std::shared_ptr<const WorkerSnapshot> snapshot() const;
  WorkerStatus status() const;
  // Blocks until nothing is running or pending (tests, batch use, screenshots).
  void wait_idle() const;

 private:
  void run();
  void publish(const std::function<void(WorkerSnapshot&)>& change);

  mutable std::mutex mutex_;
  mutable std::condition_variable wake_;
  mutable std::condition_variable idle_;
  bool stop_ = false;
  bool need_load_ = false, need_decompose_ = false, need_blend_ = false;
  std::string path_a_, path_b_;
  PrepareOptions prepare_options_;
  DecomposeParams decompose_params_;
  BlendParams blend_params_;
  WorkerStage running_ = WorkerStage::kIdle;
  JobControl control_;
  std::shared_ptr<const WorkerSnapshot> snapshot_;
  std::thread thread_;
};

}  // namespace mostyle
