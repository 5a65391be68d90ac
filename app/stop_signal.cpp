#include "app/stop_signal.h"

#include <pthread.h>

#include <initializer_list>

namespace mostyle::cli {

StopSignal::StopSignal() {
  sigemptyset(&signals_);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&signals_, sig);
  pthread_sigmask(SIG_BLOCK, &signals_, &previous_mask_);
  thread_ = std::thread([this] {
    int sig = 0;
    while (sigwait(&signals_, &sig) != 0) {
    }
    // The destructor's own wake-up is not a request.
    if (!done_.load()) requested_.store(sig);
  });
}

StopSignal::~StopSignal() {
  done_.store(true);
  if (requested_.load() == 0) pthread_kill(thread_.native_handle(), SIGTERM);
  thread_.join();
  const int sig = requested_.load();
  if (sig != 0) {
    // Ends the process as the signal would have; the caller has written what it had to.
    signal(sig, SIG_DFL);
    pthread_sigmask(SIG_SETMASK, &previous_mask_, nullptr);
    raise(sig);
  }
  pthread_sigmask(SIG_SETMASK, &previous_mask_, nullptr);
}

}  // namespace mostyle::cli
