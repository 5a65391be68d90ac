#pragma once
// The engine's worker thread: runs the slow stages of the one chain (load and prepare_takes,
// decompose_takes) off the caller's thread, for 2 to 16 takes; a pair is two. The mix
// (mix_palette) is fast and runs where its result is shown (the editor's ResultView). A request
// replaces pending work of its stage; a running job that a request makes stale is cancelled at its
// next check. Results are immutable snapshots, readable at any time from any thread. Every
// exception becomes an error sentence in the snapshot; what was loaded before an error stays.
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "engine/io/bvh/bvh_read.h"
#include "engine/base/job_control.h"
#include "engine/synthesize/mix_palette.h"

namespace mostyle {

struct WorkerSnapshot {
  std::vector<std::string> paths;                 // files of `prepared`, the reference first
  std::shared_ptr<const PreparedTakes> prepared;  // null until a load succeeds
  std::shared_ptr<const Decomposed> decomposed;   // of `prepared`; null until its first one
  // The request `decomposed` was made from. More than two takes are decomposed in shared mode
  // without basic motions whatever this says; the decomposition's own params hold what it used.
  DecomposeParams decompose_params;
  // Beside the stage values: how long reading and preparing `prepared` (load, preprocess, dtw)
  // and making `decomposed` (decompose) took.
  StageTimes times;
  std::string error;                  // the last failed request's sentence; empty after a success
  std::vector<std::string> warnings;  // from loading `prepared`
  std::uint64_t version = 0;          // grows with every published change
};

// The stages: kLoading (read and prepare_takes), kDecomposing (decompose_takes).
enum class WorkerStage { kIdle, kLoading, kDecomposing };
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

  // Loads and prepares 2 to kMaxPaletteTakes takes (paths[0] the reference; a path given twice
  // is read once; one path: the take with itself), then decomposes them with the current
  // parameters (more than two takes: in shared mode without basic motions, which are two
  // takes'). Replaces a pending load; cancels a running load or decomposition. Cost: reading
  // the files, then prepare_takes.
  void load(const std::vector<std::string>& paths, const PrepareOptions& options = {});
  // New decomposition parameters: decomposes again. Cancels a running decomposition.
  void decompose(const DecomposeParams& params);

  std::shared_ptr<const WorkerSnapshot> snapshot() const;
  WorkerStatus status() const;
  // Blocks until nothing is running or pending (tests, batch use, screenshots).
  void wait_idle() const;
  // Called on the worker's thread after each job (a load, a decomposition, a failure or a
  // cancellation), once its snapshot and status are published, so that an event
  // loop waiting for input can wake and show it. Empty: none. Must be safe to call from another
  // thread (a GLFW empty event is); it may read the snapshot and the status.
  void set_on_change(std::function<void()> notify);

 private:
  void run();
  // The jobs run() picks from: each is called with `lock` held, unlocks it while it works and
  // holds it again when it returns (an exception may leave it unlocked; run() relocks).
  void run_load(std::unique_lock<std::mutex>& lock);
  void run_decompose(std::unique_lock<std::mutex>& lock);
  bool has_work() const;  // with mutex_ held: a request that can run now
  void publish(const std::function<void(WorkerSnapshot&)>& change);

  mutable std::mutex mutex_;
  mutable std::condition_variable wake_;
  mutable std::condition_variable idle_;
  bool stop_ = false;
  bool need_load_ = false, need_decompose_ = false;
  std::vector<std::string> paths_;
  const BvhReadOptions read_options_;  // set before the thread starts, never changed
  PrepareOptions prepare_options_;
  DecomposeParams decompose_params_;
  WorkerStage running_ = WorkerStage::kIdle;
  JobControl control_;
  std::shared_ptr<const WorkerSnapshot> snapshot_;
  std::function<void()> on_change_;
  std::thread thread_;
};

}  // namespace mostyle
