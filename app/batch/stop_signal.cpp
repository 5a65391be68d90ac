#include "app/batch/stop_signal.h"

#include <pthread.h>

#include <initializer_list>

namespace mostyle::cli {
namespace {

constexpr int kWakeUp = SIGUSR2;

}  // namespace

StopSignal::StopSignal() {
  sigemptyset(&signals_);
  // A signal the process was started with ignored (nohup's SIGHUP, SIGINT in a background job of
  // a script) stays ignored, for batch and its jobs alike.
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction current {};
    if (sigaction(sig, nullptr, &current) == 0 && current.sa_handler == SIG_IGN) continue;
    sigaddset(&signals_, sig);
  }
  // The destructor's wake-up call (one from elsewhere is not a request).
  sigaddset(&signals_, kWakeUp);
  pthread_sigmask(SIG_BLOCK, &signals_, &previous_mask_);
  thread_ = std::thread([this] {
    for (;;) {
      int sig = 0;
      if (sigwait(&signals_, &sig) != 0) continue;
      if (sig == kWakeUp) {
        if (done_.load()) return;
        continue;
      }
      // The first signal stops the jobs with itself; another one after it, with SIGKILL.
      int expected = 0;
      if (!requested_.compare_exchange_strong(expected, sig)) requested_.store(SIGKILL);
      if (first_ == 0) first_ = sig;
    }
  });
}

StopSignal::~StopSignal() {
  done_.store(true);
  pthread_kill(thread_.native_handle(), kWakeUp);
  thread_.join();
  if (first_ != 0) {
    // Ends the process as the signal would have; the caller has written what it had to.
    signal(first_, SIG_DFL);
    pthread_sigmask(SIG_SETMASK, &previous_mask_, nullptr);
    raise(first_);
  }
  pthread_sigmask(SIG_SETMASK, &previous_mask_, nullptr);
}

}  // namespace mostyle::cli
