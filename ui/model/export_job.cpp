#include "ui/model/export_job.h"

#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <system_error>
#include <utility>

#include "engine/export/export_frames.h"
#include "engine/base/clock.h"
#include "engine/base/error.h"
#include "engine/kinematics/units.h"
#include "ui/model/engine_link.h"
#include "engine/base/numbers.h"

namespace mostyle::ui {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;
// Progress once the frames are resampled: the solve and the write are the rest.
constexpr float kResampledProgress = 0.1f;

}  // namespace

ExportSubject export_subject(const EngineLink& engine) {
  ExportSubject subject;
  if (const PreparedTakes* takes = engine.snapshot().prepared.get()) {
    subject.identity = takes;
    subject.clip = takes->reference().clip.get();
    subject.working_fps = takes->fps;
    subject.takes = takes->size();
    if (const MixResult* result = engine.result()) {
      subject.frames = static_cast<int>(result->motion.world.rows());
      subject.loop_cycles = result->motion.loop.cycles;
    }
  }
  if (subject.clip != nullptr) subject.name = fs::path(subject.clip->source).filename().string();
  return subject;
}

ExportRequest make_export_request(const EngineLink& engine, const ExportOptions& options) {
  if (options.path.empty()) throw InputError("Export: no file name given.");
  const std::shared_ptr<const PreparedTakes> takes = engine.snapshot().prepared;
  const MixResult* result = engine.result();
  const std::string what = result_name(takes != nullptr ? takes->size() : 2, false);
  if (takes == nullptr || result == nullptr || result->motion.world.rows() == 0)
    throw InputError("Export: nothing to export yet (no " + what + ").");
  if (options.range == ExportRange::kLoop && result->motion.loop.cycles <= 0)
    throw InputError("Export: the " + what + " has no loop; turn on Loop in the parameters panel, or export all frames.");
  ExportRequest r;
  r.clip = takes->reference().clip;
  r.joints = export_joints(*takes);
  r.world = result->motion.world;
  r.at = source_frames_in_clip(*takes, *result);
  r.working_fps = takes->fps;
  r.loop_travel = result->motion.loop.travel;
  r.options = options;
  // Resolved now: the working folder is the one the person saw when they pressed Export.
  std::error_code ec;
  const fs::path absolute = fs::absolute(fs::path(options.path), ec);
  if (!ec) r.options.path = absolute.string();
  return r;
}

ExportOutcome run_export(const ExportRequest& request, JobControl* control) {
  const auto t0 = Clock::now();
  const ExportOptions& o = request.options;
  ExportOutcome out;
  out.path = o.path;
  try {
    if (request.clip == nullptr) throw InputError("Export: nothing to export yet (no blend).");
    check_cancel(control);
    const double fps = o.fps;  // checked by export_frames: a sentence for 0, a negative or a typo
    ExportFrames frames;
    switch (o.range) {
      case ExportRange::kAll:
        frames = export_frames(request.world, request.at, request.working_fps, fps, 0.0,
                               motion_length_s(request.world.rows(), request.working_fps));
        break;
      case ExportRange::kInOut:
        frames = export_frames(request.world, request.at, request.working_fps, fps, o.in_s, o.out_s);
        break;
      case ExportRange::kLoop:
        frames = export_loop_frames(request.world, request.at, request.working_fps, fps, request.loop_travel);
        break;
    }
    report_progress(control, kResampledProgress);
    check_cancel(control);
    const ExportResult result =
        export_blend_bvh(*request.clip, request.joints, frames.world, frames.at, fps, o.path, o.layout);
    report_progress(control, 1.0f);
    out.ok = true;
    out.frames = result.clip.frames();
    out.fps = fps;
    out.fit = result.fit;

    // The fit in metric units when A's unit can be guessed (as the metrics panel says lengths).
    const UnitsGuess units = guess_units(*request.clip);
    const double cm_per_unit = centimetres_per_unit(units.name);
    const std::string worst = length_in_words(result.fit.max, cm_per_unit, units.height);
    const std::string mean = length_in_words(result.fit.mean, cm_per_unit, units.height);
    // A loop lasts all its frames (the next repeat follows the last); a clip, first to last.
    const double seconds = o.range == ExportRange::kLoop ? out.frames / fps : motion_length_s(out.frames, fps);
    const std::string reference = fs::path(request.clip->source).filename().string();
    char text[160];
    std::snprintf(text, sizeof text, "Exported %d frames at %g fps (%s%s, ", out.frames, fps,
                  duration_in_words(seconds).c_str(), o.range == ExportRange::kLoop ? ", a seamless loop" : "");
    out.message = text + (o.layout == ChannelLayout::kRotations ? "rotation channels" : "the channels of " + reference) +
                  ") to " + o.path + ". The skeleton of " + reference + " in the file follows the result within " +
                  worst + " (worst joint and frame; " + mean + " on average).";
  } catch (const Cancelled&) {
    out.cancelled = true;
    out.message = "Export cancelled: nothing was written.";
  } catch (const std::exception& e) {  // InputError: a bad rate or range, a file that cannot be written
    out.message = e.what();
  }
  out.ms = ms_since(t0);
  return out;
}

ExportJob::~ExportJob() {
  cancel();
  wait();
}

bool ExportJob::start(ExportRequest request) {
  if (running_.load()) return false;
  if (thread_.joinable()) thread_.join();  // the previous export, finished: its outcome is stored
  control_.cancel.store(false);
  control_.progress.store(0.0f);
  running_.store(true);
  try {
    thread_ = std::thread([this, r = std::move(request)]() {
      ExportOutcome outcome = run_export(r, &control_);
      {
        std::lock_guard<std::mutex> lock(mutex_);
        outcome_ = std::move(outcome);
        has_outcome_ = true;
      }
      running_.store(false);
    });
  } catch (const std::system_error& e) {  // no thread to be had: said as any failed export
    std::lock_guard<std::mutex> lock(mutex_);
    outcome_ = ExportOutcome();
    outcome_.message = std::string("Export: could not start it (") + e.what() + ").";
    has_outcome_ = true;
    running_.store(false);
  }
  return true;
}

bool ExportJob::take_outcome(ExportOutcome* out) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!has_outcome_) return false;
  *out = std::move(outcome_);
  outcome_ = ExportOutcome();
  has_outcome_ = false;
  return true;
}

bool ExportJob::has_outcome() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return has_outcome_;
}

void ExportJob::wait() {
  if (thread_.joinable()) thread_.join();
}

}  // namespace mostyle::ui
