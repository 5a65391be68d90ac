#pragma once
// Turns SIGINT, SIGTERM and SIGHUP into a request to stop, for `mostyle-cli batch`: its jobs lead
// process groups of their own, so a Ctrl-C in the terminal or a scheduler's SIGTERM to batch
// alone would not reach them, and batch would die without its summary.
#include <signal.h>

#include <atomic>
#include <thread>

namespace mostyle::cli {

class StopSignal {
 public:
  // Blocks the three signals in the calling thread (and so in the threads it starts afterwards)
  // and starts a thread that waits for them: the first one's number goes to requested(), and
  // any signal after it makes requested() SIGKILL. A signal the process was started with
  // ignored stays ignored. Construct it on the thread that starts the others, before it does.
  StopSignal();
  // Stops the waiting thread and restores the signal mask. When a signal came, the first one is
  // then raised again with its default action, so the process ends as that signal ends it.
  ~StopSignal();
  StopSignal(const StopSignal&) = delete;
  StopSignal& operator=(const StopSignal&) = delete;

  // 0 until a signal came; then its number; SIGKILL after a second one.
  const std::atomic<int>& requested() const { return requested_; }

 private:
  sigset_t signals_{};
  sigset_t previous_mask_{};
  std::atomic<int> requested_{0};
  std::atomic<bool> done_{false};
  int first_ = 0;  // the first signal; written by the waiting thread, read after joining it
  std::thread thread_;
};

}  // namespace mostyle::cli
