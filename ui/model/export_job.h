#pragma once
// The export of the blend, off the UI thread: a
// request copied from the engine link (so the blend may change while the file is written), the
// export itself (engine/export/export_frames.h, then export_solve.h export_blend_bvh) and a
// small job that runs it on a thread of its own with progress and cancel (engine JobControl).
#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/Core>

#include "engine/export/channel_layout.h"
#include "engine/export/export_solve.h"
#include "engine/base/clip.h"
#include "engine/base/job_control.h"

namespace mostyle::ui {

class EngineLink;

// Which frames of the blend an export writes.
enum class ExportRange {
  kAll,    // every frame, first to last
  kInOut,  // from the in point to the out point, both included
  kLoop,   // the blend's seamless loop (FinishOptions::loop), resampled so that it still repeats
           // without a hitch at the output rate (export_frames.h export_loop_frames)
};

// What an export asks for beyond the blend itself.
struct ExportOptions {
  std::string path;        // the file; a relative path is taken from the working folder
  double fps = 30.0;       // output frame rate, frames per second (the export refuses <= 0 or > 1000)
  ExportRange range = ExportRange::kAll;
  double in_s = 0.0;       // kInOut: seconds of the blend (its first frame at 0), in_s <= out_s
  double out_s = 0.0;
  ChannelLayout layout = ChannelLayout::kAsSource;  // the caller's default: default_channel_layout(A)
};

// What the engine link shows, as the export dialog needs it each frame, whatever the number of takes:
// the reference take (A, or a palette's first) and the result on it (the blend or the mix).
struct ExportSubject {
  const void* identity = nullptr;  // the prepared pair or palette: a new one resets the dialog
  const Clip* clip = nullptr;      // the reference take as loaded; null: nothing loaded
  std::string name;                // its file's name, for the dialog's words
  double working_fps = 30.0;       // the result's rate
  int frames = 0;                  // the result's frames; 0: none yet
  int loop_cycles = 0;             // of the result's loop; 0: none
  int takes = 0;                   // 2 for a pair, N for a palette
};
// O(1): no copy of the result.
ExportSubject export_subject(const EngineLink& engine);

// Everything one export needs, copied out of the engine link: the job never reads it.
struct ExportRequest {
  std::shared_ptr<const Clip> clip;  // take A as loaded (immutable, shared with the engine link)
  std::vector<int> joints;           // A's joint of each major column (prepare_takes.h export_joints)
  Eigen::MatrixXd world;             // F x 3M: the blend at working_fps, A's units and world
  Eigen::VectorXd at;                // F: A's clip frame each blend frame shows (source_frames_in_clip)
  double working_fps = 30.0;         // the blend's rate
  Eigen::Vector2d loop_travel = Eigen::Vector2d::Zero();  // kLoop: the root's (x, z) travel per loop
  ExportOptions options;             // the path made absolute
};

// The request for the engine link's current blend. Throws InputError with a sentence when there is
// no file name, no blend yet, or a loop asked of a blend without one. Copies the blend: O(F x 3M).
ExportRequest make_export_request(const EngineLink& engine, const ExportOptions& options);

// How an export went, in words for the person and in numbers for tests.
struct ExportOutcome {
  bool ok = false;
  bool cancelled = false;  // cancelled before the file was written (nothing written)
  std::string path;        // absolute
  std::string message;     // ok: where it went, frames, rate, and how closely the file follows
                           // the blend in metric units; else the error sentence as it is
  int frames = 0;          // written
  double fps = 0.0;
  ExportFit fit;           // A's units
  double ms = 0.0;         // wall time
};

// Resamples (export_frames or export_loop_frames), solves A's rotations and writes the file
// atomically (export_blend_bvh). Never throws: an InputError becomes the outcome's message.
// Progress goes to `control` (0.1 resampled, 1 done); a cancel is seen before the solve starts
// (the solve and the write are not interrupted). O(K x joints) for K output frames.
ExportOutcome run_export(const ExportRequest& request, JobControl* control = nullptr);

// One export at a time on a thread of its own. The UI thread calls start(), then each frame
// progress() and take_outcome(); nothing here blocks except wait() and the destructor.
class ExportJob {
 public:
  ExportJob() = default;
  ~ExportJob();  // cancels a running export and waits for its thread
  ExportJob(const ExportJob&) = delete;
  ExportJob& operator=(const ExportJob&) = delete;

  // Starts run_export(request) on a new thread; false (and nothing started) while one runs.
  bool start(ExportRequest request);
  bool running() const { return running_.load(); }
  float progress() const { return control_.progress.load(); }
  void cancel() { control_.cancel.store(true); }
  // The finished export's outcome, once: true when there was one (then *out holds it).
  bool take_outcome(ExportOutcome* out);
  // A finished export's outcome waits for take_outcome.
  bool has_outcome() const;
  // Blocks until the running export (if any) has finished (tests).
  void wait();

 private:
  std::thread thread_;
  JobControl control_;
  std::atomic<bool> running_{false};
  mutable std::mutex mutex_;  // guards outcome_ and has_outcome_
  ExportOutcome outcome_;
  bool has_outcome_ = false;
};

}  // namespace mostyle::ui
