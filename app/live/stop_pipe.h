#pragma once
// SIGINT and SIGTERM as a descriptor a poll loop watches: `live` and `live-send` end cleanly
// (recordings complete, a summary) instead of dying mid-write.
#include <signal.h>

namespace mostyle::live {

class StopPipe {
 public:
  // Catches SIGINT and SIGTERM (unless the process was started with them ignored) until
  // destroyed; one StopPipe at a time.
  StopPipe();
  ~StopPipe();  // the signals' previous actions back
  StopPipe(const StopPipe&) = delete;
  StopPipe& operator=(const StopPipe&) = delete;

  // Readable once a signal came: poll it for POLLIN.
  int fd() const;
  // The first signal caught, 0 before any.
  int signal() const;

 private:
  struct sigaction previous_int_ {}, previous_term_ {};
};

}  // namespace mostyle::live
