#pragma once
// Runs many commands as child processes, a few at a time (mostyle-cli batch). Each job is its
// own process, so a crash or an out-of-memory kill in one is that job's failure only.
#include <atomic>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace mostyle::cli {

struct JobResult;

struct JobRunnerOptions {
  // Executable every job runs. "/proc/self/exe" (Linux) is this very program, even when its
  // file has been replaced or deleted since it started.
  std::string program = "/proc/self/exe";
  int parallel = 1;  // children running at once, >= 1
  // Seconds a job may run; a job still running then is stopped: SIGTERM to its process group,
  // SIGKILL grace_seconds later if it is still there. 0: no limit.
  double timeout_seconds = 0.0;
  double grace_seconds = 5.0;  // > 0
  // Runs more of a job that was killed by a signal (a crash, an out-of-memory kill); a job that
  // exited (bad input: 1, bad usage: 2, ...), timed out or could not start is never run again.
  int retries = 0;
  // Called once per job as it finishes (after its last attempt), one call at a time, from the
  // thread that ran it; `index` is the job's place in `jobs`. Must not throw. May be empty.
  std::function<void(size_t index, const JobResult& result)> on_finished;
  // When another thread stores a signal number here, every running job's process group is sent
  // that signal (and is not run again; a later, other number is sent too), and the jobs not
  // started yet are not started: their error is "not run: stopped by signal N (name)". Null:
  // never stopped. Checked every 100 ms until SIGKILL was sent.
  const std::atomic<int>* stop = nullptr;

  // Throws InputError on an empty program, parallel < 1, a negative or non-finite timeout, a
  // grace that is not positive and finite, or retries < 0.
  void Validate() const;
};

struct JobResult {
  bool ok = false;         // the child exited with status 0
  int exit_status = -1;    // its exit status; -1 when it did not exit (killed, or could not start)
  std::string error;       // "" when ok; else one line: the child's message or why it stopped
  double seconds = 0.0;    // wall time from the first start to the last exit, over every attempt
  int attempts = 0;        // times the job was started: 1 + retries used
  bool timed_out = false;  // the last attempt was stopped at the timeout
  double max_rss_mb = 0.0;  // peak resident memory of the last attempt's process, MB (2^20 bytes)
  std::vector<int> pids;    // process id of each attempt that started, in order
};

// Runs o.program once per entry of `jobs` (the arguments after argv[0]), at most o.parallel at a
// time, and returns one result per job, in the order of `jobs`. A child inherits the working
// directory and environment (with no signal blocked); it leads a process group of its own, so a
// timeout stops whatever it started too; its stdin and stdout are /dev/null; its stderr is read
// through a pipe (the last 64 KiB kept) for the error line. A timed-out job's error is "timed
// out after S s". A job that fails, is killed or cannot start is that job's result: run_jobs
// throws only InputError from o.Validate(); on_finished is not called for a job that was not
// started. Threads: the caller and min(parallel, jobs) - 1
// more, each waiting on one child at a time (polling its stderr while a timeout runs).
std::vector<JobResult> run_jobs(const std::vector<std::vector<std::string>>& jobs, const JobRunnerOptions& o);

// A failed child's message from its stderr: the last line "mostyle: ..." that is not a warning
// ("mostyle: warning: ..."), without the "mostyle: "; when there is none, the first non-empty
// line that is not a warning (a usage error's text, a crash's); "" when stderr has neither.
std::string error_line(const std::string& stderr_text);

}  // namespace mostyle::cli
