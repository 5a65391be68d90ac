#include "app/job_runner.h"

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

#include "engine/io/error.h"

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

Attempt run_attempt(const std::string& program, const std::vector<std::string>& args, const JobRunnerOptions& o) {
  Attempt a;
  JobResult& r = a.result;
  SpawnResources res;
  // O_CLOEXEC: a child spawned meanwhile by another worker thread must not inherit this pipe,
  // or our read would wait for that child too. dup2 onto fd 2 clears the flag in our own child.
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    r.error = "cannot start: " + system_message(errno);
    return a;
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
    r.error = "cannot start " + program + ": " + system_message(spawn_error);
    return a;
  }
  r.pids.push_back(static_cast<int>(pid));

  // Reads stderr until its end, then reaps the child. With a timeout, each wait ends at the next
  // deadline: SIGTERM to the group at the timeout, SIGKILL after the grace. Its end comes when
  // every process of the group has closed it (or died).
  constexpr auto kNever = Clock::time_point::max();
  const bool limited = o.timeout_seconds > 0;
  // At most 10^9 s (32 years): more would overflow the clock's nanoseconds, and is no limit anyway.
  auto seconds = [](double s) {
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(std::min(s, 1e9)));
  };
  Clock::time_point next = limited ? start + seconds(o.timeout_seconds) : kNever;
  int stop_signal = SIGTERM;  // the next one a timeout sends
  auto on_deadline = [&] {
    if (next == kNever || Clock::now() < next) return;
    ::kill(-pid, stop_signal);
    r.timed_out = true;
    next = stop_signal == SIGTERM ? Clock::now() + seconds(o.grace_seconds) : kNever;
    stop_signal = SIGKILL;
  };
  // A stop request is passed on to the group once, and looked for at least every kStopCheck.
  constexpr int kStopCheckMs = 100;
  bool stop_passed = false;
  auto on_stop = [&] {
    if (stop_passed || o.stop == nullptr) return;
    const int sig = o.stop->load();
    if (sig == 0) return;
    ::kill(-pid, sig);
    stop_passed = true;
  };
  auto wait_ms = [&] {
    const int until_next = next == kNever ? -1 : ms_until(next);
    if (o.stop == nullptr || stop_passed) return until_next;
    return until_next < 0 ? kStopCheckMs : std::min(until_next, kStopCheckMs);
  };
  StderrTail err;
  char buffer[4096];
  for (bool open = true; open;) {
    pollfd p{res.read_fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, wait_ms());
    if (ready > 0) {
      const ssize_t n = ::read(res.read_fd, buffer, sizeof buffer);
      if (n > 0) err.append(buffer, static_cast<size_t>(n));
      else if (n == 0 || errno != EINTR) open = false;
    } else if (ready < 0 && errno != EINTR) {
      open = false;
    }
    on_deadline();
    on_stop();
  }
  int status = 0;
  rusage usage{};
  for (;;) {
    const pid_t done = ::wait4(pid, &status, wait_ms() < 0 ? 0 : WNOHANG, &usage);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) {
      r.error = "cannot wait for the job: " + system_message(errno);
      return a;
    }
    if (done == 0) {  // it closed stderr but runs on: look again shortly, or at the deadline
      std::this_thread::sleep_for(std::chrono::milliseconds(std::min(10, wait_ms())));
      on_deadline();
      on_stop();
    }
  }
  r.max_rss_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: kilobytes
  const std::string message = error_line(err.text());
  if (r.timed_out) {
    r.error = "timed out after " + number_text(o.timeout_seconds) + " s";
    return a;
  }
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
