#include "engine/worker/worker.h"

#include <chrono>
#include <functional>

#include "engine/base/clock.h"
#include "engine/io/motion_file.h"
#include "engine/base/error.h"

namespace mostyle {
namespace {

// One take of any format (FILE#ANIMATION too); which animation of several was taken is told
// with the warnings, which the editor shows.
Clip read_take(const std::string& path, std::vector<std::string>* warnings, const BvhReadOptions& read) {
  std::vector<std::string> notes;
  MotionReadOptions options;
  options.max_bytes = read.max_bytes;  // the editor's memory limit, every format alike
  Clip clip = read_motion_file(path, warnings, options, &notes);
  if (warnings != nullptr) warnings->insert(warnings->end(), notes.begin(), notes.end());
  return clip;
}

// Reads the files, each once: a path given twice shares its clip. Checks for cancellation between files, so that a new load does not wait for all.
std::vector<std::shared_ptr<const Clip>> read_clips(const std::vector<std::string>& paths,
                                                            std::vector<std::string>* warnings,
                                                            const BvhReadOptions& read, const JobControl* control) {
  std::vector<std::shared_ptr<const Clip>> clips;
  for (size_t i = 0; i < paths.size(); ++i) {
    check_cancel(control);
    size_t same = 0;
    while (same < i && paths[same] != paths[i]) ++same;
    clips.push_back(same < i ? clips[same] : std::make_shared<const Clip>(read_take(paths[i], warnings, read)));
  }
  return clips;
}

// More than two takes mix shared components only; paper mode and basic motions are two takes',
// so a palette leaves them out of the request instead of refusing it.
DecomposeParams decompose_params_for(int takes, DecomposeParams params) {
  if (takes <= 2) return params;
  params.mode = DecompositionMode::kShared;
  params.basic_motions = 0;
  params.basic_sparsities.clear();
  return params;
}

}  // namespace

const char* worker_stage_name(WorkerStage stage) {
  switch (stage) {
    case WorkerStage::kIdle: return "idle";
    case WorkerStage::kLoading: return "loading";
    case WorkerStage::kDecomposing: return "decomposing";
  }
  return "?";
}

Worker::Worker(const BvhReadOptions& read) : read_options_(read), snapshot_(std::make_shared<WorkerSnapshot>()) {
  thread_ = std::thread([this] { run(); });
}

Worker::~Worker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    control_.cancel = true;
  }
  wake_.notify_all();
  thread_.join();
}

void Worker::load(const std::vector<std::string>& paths, const PrepareOptions& options) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    paths_ = paths;
    if (paths_.size() == 1) paths_.push_back(paths_.front());  // the take with itself
    prepare_options_ = options;
    // A successful load asks for the decomposition itself; asking here would, when the load
    // fails, re-run it on the previous takes and wipe the error off the snapshot.
    need_load_ = true;
    if (running_ == WorkerStage::kLoading || running_ == WorkerStage::kDecomposing) control_.cancel = true;
  }
  wake_.notify_all();
}

void Worker::decompose(const DecomposeParams& params) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    decompose_params_ = params;
    need_decompose_ = true;
    if (running_ == WorkerStage::kDecomposing) control_.cancel = true;
  }
  wake_.notify_all();
}

std::shared_ptr<const WorkerSnapshot> Worker::snapshot() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return snapshot_;
}

WorkerStatus Worker::status() const {
  std::lock_guard<std::mutex> lock(mutex_);
  WorkerStatus s;
  s.stage = running_;
  s.progress = running_ == WorkerStage::kIdle ? 0.0f : control_.progress.load();
  s.pending = has_work();
  return s;
}

void Worker::wait_idle() const {
  std::unique_lock<std::mutex> lock(mutex_);
  idle_.wait(lock, [this] { return running_ == WorkerStage::kIdle && !has_work(); });
}

// Parameters without something to apply them to wait for it; they are not work yet.
bool Worker::has_work() const {
  const WorkerSnapshot& s = *snapshot_;
  return need_load_ || (need_decompose_ && s.prepared);
}

// Called with mutex_ held: a new snapshot made from the current one.
void Worker::publish(const std::function<void(WorkerSnapshot&)>& change) {
  auto next = std::make_shared<WorkerSnapshot>(*snapshot_);
  change(*next);
  next->version = snapshot_->version + 1;
  snapshot_ = std::move(next);
}

void Worker::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || has_work(); });
    if (stop_) return;
    control_.cancel = false;
    control_.progress = 0.0f;
    try {
      if (need_load_) run_load(lock);
      else if (need_decompose_ && snapshot_->prepared) run_decompose(lock);
    } catch (const Cancelled&) {
      if (!lock.owns_lock()) lock.lock();
    } catch (const InputError& e) {
      if (!lock.owns_lock()) lock.lock();
      const std::string message = e.what();
      publish([&](WorkerSnapshot& s) { s.error = message; });
    } catch (const std::exception& e) {
      if (!lock.owns_lock()) lock.lock();
      const std::string message = std::string("internal error: ") + e.what();
      publish([&](WorkerSnapshot& s) { s.error = message; });
    }
    running_ = WorkerStage::kIdle;
    idle_.notify_all();
    if (on_change_) {  // outside the lock: the callback may ask for the snapshot or the status
      const std::function<void()> notify = on_change_;
      lock.unlock();
      notify();
      lock.lock();
    }
  }
}

void Worker::set_on_change(std::function<void()> notify) {
  std::lock_guard<std::mutex> lock(mutex_);
  on_change_ = std::move(notify);
}

void Worker::run_load(std::unique_lock<std::mutex>& lock) {
  need_load_ = false;
  running_ = WorkerStage::kLoading;
  const std::vector<std::string> paths = paths_;
  const PrepareOptions options = prepare_options_;
  lock.unlock();
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::string> warnings;
  const auto clips = read_clips(paths, &warnings, read_options_, &control_);
  const double load_ms = ms_since(t0);
  StageTimes times;
  times.load_ms = load_ms;
  auto prepared = prepare_takes(clips, options, &control_, &times);
  lock.lock();
  publish([&](WorkerSnapshot& s) {
    s.times = times;
    s.paths = paths;
    s.prepared = prepared;
    s.decomposed = nullptr;
    s.warnings = warnings;
    s.error.clear();
  });
  need_decompose_ = true;
}

void Worker::run_decompose(std::unique_lock<std::mutex>& lock) {
  need_decompose_ = false;
  running_ = WorkerStage::kDecomposing;
  const DecomposeParams params = decompose_params_;
  const auto prepared = snapshot_->prepared;
  lock.unlock();
  StageTimes times;
  auto decomposed = decompose_takes(*prepared, decompose_params_for(prepared->size(), params), &control_, &times);
  lock.lock();
  if (snapshot_->prepared == prepared) {
    publish([&](WorkerSnapshot& s) {
      s.times.decompose_ms = times.decompose_ms;
      s.decomposed = decomposed;
      s.decompose_params = params;
      s.error.clear();
    });
  }
}

}  // namespace mostyle
