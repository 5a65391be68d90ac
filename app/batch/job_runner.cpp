#include "app/batch/job_runner.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <mutex>
#include <string_view>
#include <system_error>
#include <thread>

#include "engine/base/error.h"

extern char** environ;

namespace mostyle::cli {
namespace {

constexpr size_t kKeptStderr = 64 * 1024;  // bytes of a child's stderr kept (its end)
constexpr std::string_view kPrefix = "mostyle: ";
constexpr std::string_view kWarning = "mostyle: warning: ";

// Shortest text that reads back as the same double.
std::string number_text(double v) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, r.ptr);
}

// "signal 9 (Killed)".
std::string signal_text(int sig) {
  const char* name = ::sigdescr_np(sig);  // thread-safe, unlike strsignal
  return "signal " + std::to_string(sig) + (name ? std::string(" (") + name + ")" : "");
}

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

std::string system_message(int error) { return std::system_category().message(error); }

// A child's stderr as it arrives, keeping its last kKeptStderr bytes.
class StderrTail {
 public:
  void append(const char* data, size_t n) {
    text_.append(data, n);
    if (text_.size() > 2 * kKeptStderr) text_.erase(0, text_.size() - kKeptStderr);
  }
  std::string text() const {
    return text_.size() > kKeptStderr ? text_.substr(text_.size() - kKeptStderr) : text_;
  }

 private:
  std::string text_;
};

// Closes the pipe's read end and frees the spawn attributes on every way out of run_attempt.
struct SpawnResources {
  int read_fd = -1;
  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attributes;
  SpawnResources() {
    posix_spawn_file_actions_init(&actions);
    posix_spawnattr_init(&attributes);
  }
  ~SpawnResources() {
    if (read_fd >= 0) ::close(read_fd);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
  }
  SpawnResources(const SpawnResources&) = delete;
  SpawnResources& operator=(const SpawnResources&) = delete;
};

using Clock = std::chrono::steady_clock;

// One run of a job. `signaled`: it was killed by a signal that was not the timeout's.
struct Attempt {
  JobResult result;
  bool signaled = false;
};

int ms_until(Clock::time_point t) {
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(t - Clock::now()).count() + 1;
  return static_cast<int>(std::clamp<long long>(ms, 0, 60 * 1000));
}

// At most 10^9 s (32 years): more would overflow the clock's nanoseconds, and is no limit anyway.
Clock::duration seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(std::min(s, 1e9)));
}

// The signals a running child's process group is due: with a timeout, SIGTERM then and SIGKILL
// a grace later; on a stop request, its signal, once (and again when the request changes).
class GroupSignals {
 public:
  GroupSignals(pid_t group, Clock::time_point start, const JobRunnerOptions& o)
      : group_(group), o_(o), next_(o.timeout_seconds > 0 ? start + seconds(o.timeout_seconds) : kNever) {}

  // Sends what is due now.
  void send_due() {
    if (next_ != kNever && Clock::now() >= next_) {
      ::kill(-group_, timeout_signal_);
      timed_out_ = true;
      next_ = timeout_signal_ == SIGTERM ? Clock::now() + seconds(o_.grace_seconds) : kNever;
      timeout_signal_ = SIGKILL;
    }
    if (o_.stop != nullptr) {
      const int sig = o_.stop->load();
      if (sig != 0 && sig != stop_passed_) {
        ::kill(-group_, sig);
        stop_passed_ = sig;
      }
    }
  }
  // How long a wait may last before send_due has something to do, ms; -1: for ever.
  int wait_ms() const {
    const int until_next = next_ == kNever ? -1 : ms_until(next_);
    if (o_.stop == nullptr || stop_passed_ == SIGKILL) return until_next;
    return until_next < 0 ? kStopCheckMs : std::min(until_next, kStopCheckMs);
  }
  bool timed_out() const { return timed_out_; }

 private:
  static constexpr Clock::time_point kNever = Clock::time_point::max();
  static constexpr int kStopCheckMs = 100;  // how often a stop request is looked for
  const pid_t group_;
  const JobRunnerOptions& o_;
  Clock::time_point next_;          // the timeout's next signal; kNever: none
  int timeout_signal_ = SIGTERM;    // which one it is
  bool timed_out_ = false;
  int stop_passed_ = 0;             // the stop request's signal last sent
};

// Reads fd until every process holding its write end has closed it (or died), sending the
// group's signals as they fall due; keeps the text's end.
std::string read_until_closed(int fd, GroupSignals& signals) {
  StderrTail err;
  char buffer[4096];
  for (bool open = true; open;) {
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, signals.wait_ms());
    if (ready > 0) {
      const ssize_t n = ::read(fd, buffer, sizeof buffer);
      if (n > 0) err.append(buffer, static_cast<size_t>(n));
      else if (n == 0 || errno != EINTR) open = false;
    } else if (ready < 0 && errno != EINTR) {
      open = false;
    }
    signals.send_due();
  }
  return err.text();
}

// How a child that ended with wait status `status` went; message: its error line.
Attempt describe_end(int status, const std::string& message) {
  Attempt a;
  JobResult& r = a.result;
  if (WIFEXITED(status)) {
    r.exit_status = WEXITSTATUS(status);
    r.ok = r.exit_status == 0;
    if (r.exit_status == 2) r.error = "bad usage: " + (message.empty() ? "exit status 2" : message);
    else if (!r.ok) r.error = message.empty() ? "exit status " + std::to_string(r.exit_status) + " and no message" : message;
    return a;
  }
  r.error = "killed by " + signal_text(WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  if (!message.empty()) r.error += ": " + message;
  a.signaled = true;
  return a;
}

Attempt run_attempt(const std::string& program, const std::vector<std::string>& args, const JobRunnerOptions& o) {
  Attempt failed;
  SpawnResources res;
  // O_CLOEXEC: a child spawned meanwhile by another worker thread must not inherit this pipe,
  // or our read would wait for that child too. dup2 onto fd 2 clears the flag in our own child.
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    failed.result.error = "cannot start: " + system_message(errno);
    return failed;
  }
  res.read_fd = fds[0];
  posix_spawn_file_actions_addopen(&res.actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&res.actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&res.actions, fds[1], 2);
  // A process group of its own, so that a timeout stops what the job started as well; and no
  // signal blocked, whatever the calling thread blocks.
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setpgroup(&res.attributes, 0);
  posix_spawnattr_setsigmask(&res.attributes, &none);
  posix_spawnattr_setflags(&res.attributes, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK);

  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(program.c_str()));
  for (const std::string& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
  const auto start = Clock::now();
  pid_t pid = 0;
  const int spawn_error = ::posix_spawn(&pid, program.c_str(), &res.actions, &res.attributes, argv.data(), environ);
  ::close(fds[1]);
  if (spawn_error != 0) {
    failed.result.error = "cannot start " + program + ": " + system_message(spawn_error);
    return failed;
  }

  GroupSignals signals(pid, start, o);
  const std::string err = read_until_closed(res.read_fd, signals);
  // Reaps the child; it may have closed stderr and run on, so the signals still fall due.
  int status = 0;
  rusage usage{};
  for (;;) {
    const pid_t done = ::wait4(pid, &status, signals.wait_ms() < 0 ? 0 : WNOHANG, &usage);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) {
      failed.result.error = "cannot wait for the job: " + system_message(errno);
      failed.result.pids = {static_cast<int>(pid)};
      return failed;
    }
    if (done == 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(std::min(10, signals.wait_ms())));
      signals.send_due();
    }
  }
  Attempt a;
  if (signals.timed_out()) {
    a.result.timed_out = true;
    a.result.error = "timed out after " + number_text(o.timeout_seconds) + " s";
  } else {
    a = describe_end(status, error_line(err));
  }
  a.result.pids = {static_cast<int>(pid)};
  a.result.max_rss_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: kilobytes
  return a;
}

// Runs a job, and again while it is killed by a signal and retries are left.
JobResult run_job(const std::vector<std::string>& args, const JobRunnerOptions& o) {
  const auto t0 = Clock::now();
  Attempt a;
  int attempts = 0;
  std::vector<int> pids;
  do {
    a = run_attempt(o.program, args, o);
    pids.insert(pids.end(), a.result.pids.begin(), a.result.pids.end());
    ++attempts;
  } while (a.signaled && attempts <= o.retries && !(o.stop && o.stop->load() != 0));
  a.result.attempts = attempts;
  a.result.pids = std::move(pids);
  a.result.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return a.result;
}

}  // namespace

void JobRunnerOptions::Validate() const {
  if (program.empty()) throw InputError("expected a program for the jobs to run, found none");
  if (parallel < 1)
    throw InputError("expected 1 or more jobs at once, found " + std::to_string(parallel));
  if (!(timeout_seconds >= 0) || !std::isfinite(timeout_seconds))
    throw InputError("expected a timeout of 0 (none) or more seconds, found " + number_text(timeout_seconds));
  if (!(grace_seconds > 0) || !std::isfinite(grace_seconds))
    throw InputError("expected a grace of more than 0 seconds, found " + number_text(grace_seconds));
  if (retries < 0) throw InputError("expected 0 or more retries, found " + std::to_string(retries));
}

std::string error_line(const std::string& stderr_text) {
  std::string_view last_error, first_other;
  std::string_view rest = stderr_text;
  while (!rest.empty()) {
    const size_t end = rest.find('\n');
    std::string_view line = rest.substr(0, end);
    rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.empty() || starts_with(line, kWarning)) continue;
    if (starts_with(line, kPrefix))
      last_error = line.substr(kPrefix.size());
    else if (first_other.empty())
      first_other = line;
  }
  return std::string(last_error.empty() ? first_other : last_error);
}

std::vector<JobResult> run_jobs(const std::vector<std::vector<std::string>>& jobs, const JobRunnerOptions& o) {
  o.Validate();
  // Each worker claims the next job index atomically and writes only that job's slot; joining
  // the threads publishes the slots to the caller.
  std::vector<JobResult> results(jobs.size());
  std::atomic<size_t> next{0};
  std::mutex finished;  // one on_finished call at a time
  auto work = [&] {
    for (size_t i; (i = next.fetch_add(1)) < jobs.size();) {
      if (const int sig = o.stop ? o.stop->load() : 0) {
        results[i].error = "not run: stopped by " + signal_text(sig);
        continue;
      }
      results[i] = run_job(jobs[i], o);
      if (!o.on_finished) continue;
      std::lock_guard<std::mutex> lock(finished);
      o.on_finished(i, results[i]);
    }
  };
  const size_t workers = std::min(jobs.size(), static_cast<size_t>(o.parallel));
  std::vector<std::thread> threads;
  for (size_t k = 1; k < workers; ++k) {
    try {
      threads.emplace_back(work);
    } catch (const std::system_error&) {
      break;  // fewer at once rather than none: the calling thread works too
    }
  }
  work();
  for (std::thread& t : threads) t.join();
  return results;
}

}  // namespace mostyle::cli
