#pragma once
// Cancellation and progress shared between a long engine job and whoever waits for it.
#include <atomic>
#include <stdexcept>

namespace mostyle {

// Thrown from a job's next check after cancel was requested; never shown to a person.
class Cancelled : public std::exception {
 public:
  const char* what() const noexcept override { return "cancelled"; }
};

// Owned by the caller, read and written from any thread. A job checks it between iterations.
struct JobControl {
  std::atomic<bool> cancel{false};
  std::atomic<float> progress{0.0f};  // 0..1 of the current job

  // Throws Cancelled when cancel was requested. Cheap: one relaxed atomic load.
  void check() const {
    if (cancel.load(std::memory_order_relaxed)) throw Cancelled();
  }
};

// For jobs that take an optional control: both are no-ops on nullptr.
inline void check_cancel(const JobControl* control) {
  if (control) control->check();
}
inline void report_progress(JobControl* control, float fraction) {
  if (control) control->progress.store(fraction, std::memory_order_relaxed);
}

}  // namespace mostyle
