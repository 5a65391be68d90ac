#include "app/live/stop_pipe.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

namespace mostyle::live {
namespace {

// The handler's state: a signal handler may only touch what is async-signal-safe.
int g_pipe[2] = {-1, -1};
volatile sig_atomic_t g_signal = 0;

void on_signal(int sig) {
  const int saved = errno;
  if (g_signal == 0) g_signal = sig;
  const char byte = 1;
  const ssize_t n = ::write(g_pipe[1], &byte, 1);  // a full pipe already wakes the loop
  (void)n;
  errno = saved;
}

void catch_signal(int sig, struct sigaction* previous) {
  sigaction(sig, nullptr, previous);
  if (previous->sa_handler == SIG_IGN) return;  // nohup and background jobs keep ignoring it
  struct sigaction a {};
  a.sa_handler = on_signal;
  sigemptyset(&a.sa_mask);
  a.sa_flags = SA_RESTART;
  sigaction(sig, &a, nullptr);
}

}  // namespace

StopPipe::StopPipe() {
  if (::pipe2(g_pipe, O_NONBLOCK | O_CLOEXEC) != 0) throw std::system_error(errno, std::generic_category(), "pipe");
  g_signal = 0;
  catch_signal(SIGINT, &previous_int_);
  catch_signal(SIGTERM, &previous_term_);
}

StopPipe::~StopPipe() {
  sigaction(SIGINT, &previous_int_, nullptr);
  sigaction(SIGTERM, &previous_term_, nullptr);
  ::close(g_pipe[0]);
  ::close(g_pipe[1]);
  g_pipe[0] = g_pipe[1] = -1;
}

int StopPipe::fd() const { return g_pipe[0]; }

int StopPipe::signal() const { return g_signal; }

}  // namespace mostyle::live
