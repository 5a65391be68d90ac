#pragma once
// Runs many commands as child processes, a few at a time (mostyle-cli batch). Each job is its
// own process, so a crash or an out-of-memory kill in one is that job's failure only.
#include <string>
#include <vector>

namespace mostyle::cli {

struct JobRunnerOptions {
  // Executable every job runs. "/proc/self/exe" (Linux) is this very program, even when its
  // file has been replaced or deleted since it started.
  std::string program = "/proc/self/exe";
  int parallel = 1;  // children running at once, >= 1

  // Throws InputError on an empty program or parallel < 1.
  void Validate() const;
};

struct JobResult {
  bool ok = false;       // the child exited with status 0
  int exit_status = -1;  // its exit status; -1 when it did not exit (killed, or could not start)
  std::string error;     // "" when ok; else one line: the child's message or why it stopped
  double seconds = 0.0;  // wall time from start to exit
};

// Runs o.program once per entry of `jobs` (the arguments after argv[0]), at most o.parallel at a
// time, and returns one result per job, in the order of `jobs`. A child inherits the working
// directory and environment; its stdin and stdout are /dev/null; its stderr is read through a
// pipe (the last 64 KiB kept) for the error line. A job that fails, is killed or cannot start
// is that job's result: run_jobs throws only InputError from o.Validate(). Threads: the caller
// and min(parallel, jobs) - 1 more, each waiting on one child at a time; no timeout.
std::vector<JobResult> run_jobs(const std::vector<std::vector<std::string>>& jobs, const JobRunnerOptions& o);

// A failed child's message from its stderr: the last line "mostyle: ..." that is not a warning
// ("mostyle: warning: ..."), without the "mostyle: "; when there is none, the first non-empty
// line that is not a warning (a usage error's text, a crash's); "" when stderr has neither.
std::string error_line(const std::string& stderr_text);

}  // namespace mostyle::cli
