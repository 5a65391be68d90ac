#include "app/job_runner.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
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

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

std::string system_message(int error) { return std::system_category().message(error); }

// Reads fd to its end, keeping the last kKeptStderr bytes.
std::string read_tail(int fd) {
  std::string text;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      break;
    }
    text.append(buffer, static_cast<size_t>(n));
    if (text.size() > 2 * kKeptStderr) text.erase(0, text.size() - kKeptStderr);
  }
  if (text.size() > kKeptStderr) text.erase(0, text.size() - kKeptStderr);
  return text;
}

// Closes the pipe's read end and the spawn attributes on every way out of run_one.
struct SpawnResources {
  int read_fd = -1;
  posix_spawn_file_actions_t actions;
  SpawnResources() { posix_spawn_file_actions_init(&actions); }
  ~SpawnResources() {
    if (read_fd >= 0) ::close(read_fd);
    posix_spawn_file_actions_destroy(&actions);
  }
  SpawnResources(const SpawnResources&) = delete;
  SpawnResources& operator=(const SpawnResources&) = delete;
};

JobResult run_one(const std::string& program, const std::vector<std::string>& args) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  JobResult r;
  auto finish = [&](std::string error) {
    r.error = std::move(error);
    r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return r;
  };

  SpawnResources res;
  // O_CLOEXEC: a child spawned meanwhile by another worker thread must not inherit this pipe,
  // or our read would wait for that child too. dup2 onto fd 2 clears the flag in our own child.
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) return finish("cannot start: " + system_message(errno));
  res.read_fd = fds[0];
  posix_spawn_file_actions_addopen(&res.actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&res.actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&res.actions, fds[1], 2);

  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(program.c_str()));
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawn_error = ::posix_spawn(&pid, program.c_str(), &res.actions, nullptr, argv.data(), environ);
  ::close(fds[1]);
  if (spawn_error != 0) return finish("cannot start " + program + ": " + system_message(spawn_error));

  const std::string err = read_tail(res.read_fd);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return finish("cannot wait for the job: " + system_message(errno));
  }
  const std::string message = error_line(err);
  if (WIFEXITED(status)) {
    r.exit_status = WEXITSTATUS(status);
    r.ok = r.exit_status == 0;
    if (r.ok) return finish("");
    if (r.exit_status == 2) return finish("bad usage: " + (message.empty() ? "exit status 2" : message));
    return finish(message.empty() ? "exit status " + std::to_string(r.exit_status) + " and no message" : message);
  }
  const int sig = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  const char* name = ::sigdescr_np(sig);  // thread-safe, unlike strsignal
  std::string error = "killed by signal " + std::to_string(sig) + (name ? std::string(" (") + name + ")" : "");
  if (!message.empty()) error += ": " + message;
  return finish(error);
}

}  // namespace

void JobRunnerOptions::Validate() const {
  if (program.empty()) throw InputError("expected a program for the jobs to run, found none");
  if (parallel < 1)
    throw InputError("expected 1 or more jobs at once, found " + std::to_string(parallel));
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
  auto work = [&] {
    for (size_t i; (i = next.fetch_add(1)) < jobs.size();) results[i] = run_one(o.program, jobs[i]);
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
