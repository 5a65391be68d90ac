#include "engine/run/worker.h"

#include <chrono>
#include <functional>

#include "engine/io/bvh_io.h"
#include "engine/io/error.h"

namespace mostyle {

const char* worker_stage_name(WorkerStage stage) {
  switch (stage) {
    case WorkerStage::kIdle: return "idle";
    case WorkerStage::kLoading: return "loading";
    case WorkerStage::kDecomposing: return "decomposing";
    case WorkerStage::kBlending: return "blending";
  }
  return "?";
}

Worker::Worker() : snapshot_(std::make_shared<WorkerSnapshot>()) { thread_ = std::thread([this] { run(); }); }

Worker::~Worker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    control_.cancel = true;
  }
  wake_.notify_all();
  thread_.join();
}

void Worker::load(const std::string& path_a, const std::string& path_b, const PrepareOptions& options) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    path_a_ = path_a;
    path_b_ = path_b.empty() ? path_a : path_b;
    prepare_options_ = options;
    // A successful load asks for the decomposition and blend itself; asking here would, when the
    // load fails, re-run them on the previous pair and wipe the error off the snapshot.
    need_load_ = true;
    if (running_ == WorkerStage::kLoading || running_ == WorkerStage::kDecomposing) control_.cancel = true;
  }
  wake_.notify_all();
}

void Worker::decompose(const DecomposeParams& params) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    decompose_params_ = params;
    need_decompose_ = true;  // a successful decomposition asks for the blend (see load)
    if (running_ == WorkerStage::kDecomposing) control_.cancel = true;
  }
  wake_.notify_all();
}

void Worker::blend(const BlendParams& params) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    blend_params_ = params;
    need_blend_ = true;
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
  s.pending = need_load_ || (need_decompose_ && snapshot_->prepared) || (need_blend_ && snapshot_->decomposed);
  return s;
}

void Worker::wait_idle() const {
  std::unique_lock<std::mutex> lock(mutex_);
  idle_.wait(lock, [this] {
    const bool pending = need_load_ || (need_decompose_ && snapshot_->prepared) ||
                         (need_blend_ && snapshot_->decomposed);
    return running_ == WorkerStage::kIdle && !pending;
  });
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
    wake_.wait(lock, [this] {
      return stop_ || need_load_ || (need_decompose_ && snapshot_->prepared) ||
             (need_blend_ && snapshot_->decomposed);
    });
    if (stop_) return;
    control_.cancel = false;
    control_.progress = 0.0f;
    try {
      if (need_load_) {
        need_load_ = false;
        running_ = WorkerStage::kLoading;
        const std::string a = path_a_, b = path_b_;
        const PrepareOptions options = prepare_options_;
        lock.unlock();
        const auto t0 = std::chrono::steady_clock::now();
        std::vector<std::string> warnings;
        auto clip_a = std::make_shared<const Clip>(read_bvh_file(a, &warnings));
        auto clip_b = b == a ? clip_a : std::make_shared<const Clip>(read_bvh_file(b, &warnings));
        const double load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        auto prepared = prepare_pair(clip_a, clip_b, options, &control_);
        std::const_pointer_cast<PreparedPair>(prepared)->times.load_ms = load_ms;
        lock.lock();
        publish([&](WorkerSnapshot& s) {
          s.prepared = prepared;
          s.decomposed = nullptr;
          s.blend = nullptr;
          s.path_a = a;
          s.path_b = b;
          s.warnings = warnings;
          s.error.clear();
        });
        need_decompose_ = need_blend_ = true;
      } else if (need_decompose_ && snapshot_->prepared) {
        need_decompose_ = false;
        running_ = WorkerStage::kDecomposing;
        const DecomposeParams params = decompose_params_;
        const auto prepared = snapshot_->prepared;
        lock.unlock();
        auto decomposed = decompose_pair(*prepared, params, &control_);
        lock.lock();
        if (snapshot_->prepared == prepared) {
          publish([&](WorkerSnapshot& s) {
            s.decomposed = decomposed;
            s.decompose_params = params;
            s.error.clear();
          });
          need_blend_ = true;
        }
      } else if (need_blend_ && snapshot_->decomposed) {
        need_blend_ = false;
        running_ = WorkerStage::kBlending;
        const BlendParams params = blend_params_;
        const auto prepared = snapshot_->prepared;
        const auto decomposed = snapshot_->decomposed;
        lock.unlock();
        BlendScratch scratch;
        auto result = std::make_shared<BlendResult>();
        blend_pair(*prepared, *decomposed, params, scratch, *result);
        lock.lock();
        if (snapshot_->decomposed == decomposed) {
          publish([&](WorkerSnapshot& s) {
            s.blend = result;
            s.blend_params = params;
            s.error.clear();
          });
        }
      }
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
  }
}

}  // namespace mostyle
